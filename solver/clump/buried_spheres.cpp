#include "solver/clump/buried_spheres.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>

namespace seedcal {

double protrusion_fraction(const SphereXYZR& i, const SphereXYZR& j) {
  return ((i.centre_m - j.centre_m).norm() + i.radius_m - j.radius_m) / i.radius_m;
}

std::vector<BuriedSphere> buried_spheres(const std::vector<SphereXYZR>& spheres, double tolerance_fraction) {
  const std::size_t n = spheres.size();
  std::vector<std::size_t> by_x(n);
  std::iota(by_x.begin(), by_x.end(), std::size_t{0});
  std::sort(by_x.begin(), by_x.end(), [&](std::size_t a, std::size_t b) {
    return spheres[a].centre_m.x() < spheres[b].centre_m.x() ||
           (spheres[a].centre_m.x() == spheres[b].centre_m.x() && a < b);
  });
  double r_max = 0.0;
  for (const auto& s : spheres) r_max = std::max(r_max, s.radius_m);
  std::vector<BuriedSphere> out;
  for (std::size_t i = 0; i < n; ++i) {
    const SphereXYZR& si = spheres[i];
    // Sphere j can hold i only if |x_i - x_j| <= d <= r_j - r_i + tol r_i <= r_max + tol r_i.
    const double reach = r_max + std::max(0.0, tolerance_fraction) * si.radius_m;
    const auto first = std::lower_bound(by_x.begin(), by_x.end(), si.centre_m.x() - reach,
                                        [&](std::size_t a, double x) { return spheres[a].centre_m.x() < x; });
    BuriedSphere worst{i, i, tolerance_fraction};
    bool found = false;
    for (auto it = first; it != by_x.end() && spheres[*it].centre_m.x() <= si.centre_m.x() + reach; ++it) {
      const std::size_t j = *it;
      if (j == i) continue;
      const double p = protrusion_fraction(si, spheres[j]);
      if (p > tolerance_fraction) continue;
      // Two spheres each within tolerance of the other (equal or nearly so): the later one is the
      // redundant copy.
      if (protrusion_fraction(spheres[j], si) <= tolerance_fraction && j > i) continue;
      if (!found || p < worst.protrusion_fraction) worst = {i, j, p};
      found = true;
    }
    if (found) out.push_back(worst);
  }
  return out;
}

std::vector<Vec3> fibonacci_directions(int n) {
  std::vector<Vec3> out;
  out.reserve(static_cast<std::size_t>(std::max(n, 0)));
  const double golden_angle = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (int k = 0; k < n; ++k) {
    const double z = 1.0 - 2.0 * (k + 0.5) / n;
    const double rho = std::sqrt(std::max(0.0, 1.0 - z * z));
    out.emplace_back(rho * std::cos(golden_angle * k), rho * std::sin(golden_angle * k), z);
  }
  return out;
}

double union_reach_fraction(const std::vector<SphereXYZR>& spheres, std::size_t i,
                            const std::vector<Vec3>& directions) {
  const SphereXYZR& si = spheres[i];
  double reach = -std::numeric_limits<double>::infinity();
  for (const Vec3& u : directions) {
    const Vec3 x = si.centre_m + si.radius_m * u;
    double d = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < spheres.size() && d > reach; ++j)
      if (j != i) d = std::min(d, (x - spheres[j].centre_m).norm() - spheres[j].radius_m);
    reach = std::max(reach, d);
  }
  return reach / si.radius_m;
}

}  // namespace seedcal
