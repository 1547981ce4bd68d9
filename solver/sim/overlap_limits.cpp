#include "solver/sim/overlap_limits.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace seedcal {

std::vector<double> sphere_overlap_limits(const BodyState& bodies, const SphereState& spheres,
                                          const std::vector<Material>& materials,
                                          const GuardOptions& guards) {
  std::vector<double> limit(spheres.size(), 0.0);
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const std::uint32_t first = bodies.first_sphere[b], end = bodies.first_sphere[b + 1];
    if (end - first == 1) {
      limit[first] = guards.max_overlap_fraction * spheres.radius_m[first];
      continue;
    }
    double r_max = 0.0;
    for (std::uint32_t i = first; i < end; ++i) r_max = std::max(r_max, spheres.radius_m[i]);
    const double rho = materials[spheres.material[first]].density_kg_m3;
    const double r_eq = std::cbrt(3.0 * bodies.mass_kg[b] / (4.0 * std::numbers::pi * rho));
    const double body_limit = guards.max_overlap_fraction * std::max(r_eq, r_max);
    for (std::uint32_t i = first; i < end; ++i)
      limit[i] = std::min(body_limit, guards.max_clump_sphere_overlap_fraction * spheres.radius_m[i]);
  }
  return limit;
}

double overlap_prefilter_fraction(const GuardOptions& guards) {
  return std::min(guards.max_overlap_fraction, guards.max_clump_sphere_overlap_fraction);
}

}  // namespace seedcal
