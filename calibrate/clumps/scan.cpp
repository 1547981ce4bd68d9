#include "calibrate/clumps/scan.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <stdexcept>

namespace seedcal {
namespace {

using Cell = std::array<long long, 3>;

Cell cell_of(const Vec3& p, double h) {
  auto c = [h](double x) { return static_cast<long long>(std::clamp(std::floor(x / h), -4.0e18, 4.0e18)); };
  return {c(p.x()), c(p.y()), c(p.z())};
}

}  // namespace

double metres_per_unit(const std::string& unit) {
  if (unit == "m") return 1.0;
  if (unit == "mm") return 1e-3;
  throw std::invalid_argument("unit = '" + unit + "': allowed m, mm (the unit the scan's coordinates are in)");
}

std::string unit_name(double metres_per_unit) { return metres_per_unit == 1e-3 ? "mm" : "m"; }

WeldResult weld_vertices(const std::vector<Triangle>& triangles, double tolerance_m) {
  WeldResult r;
  std::vector<Vec3> kept;                      // representatives, in file order
  std::map<Cell, std::vector<std::size_t>> grid;  // cell -> representatives in it
  std::map<std::array<double, 3>, std::size_t> exact;  // exact position -> representative
  const bool by_distance = tolerance_m > 0.0;
  auto index_of = [&](const Vec3& p) {
    const std::array<double, 3> key{p.x(), p.y(), p.z()};
    if (const auto it = exact.find(key); it != exact.end()) return it->second;
    std::size_t found = kept.size();
    if (by_distance) {
      const Cell c = cell_of(p, tolerance_m);
      for (long long dx = -1; dx <= 1 && found == kept.size(); ++dx)
        for (long long dy = -1; dy <= 1 && found == kept.size(); ++dy)
          for (long long dz = -1; dz <= 1 && found == kept.size(); ++dz) {
            const auto it = grid.find({c[0] + dx, c[1] + dy, c[2] + dz});
            if (it == grid.end()) continue;
            for (const std::size_t k : it->second)
              if ((kept[k] - p).norm() < tolerance_m) {
                found = k;
                break;
              }
          }
      if (found == kept.size()) grid[c].push_back(found);
    }
    if (found == kept.size()) kept.push_back(p);
    exact.emplace(key, found);
    return found;
  };
  for (const Triangle& t : triangles) {
    const std::size_t a = index_of(t[0]), b = index_of(t[1]), c = index_of(t[2]);
    if (a == b || b == c || a == c) {
      ++r.degenerate_dropped;
      continue;
    }
    r.triangles.push_back({kept[a], kept[b], kept[c]});
  }
  r.vertices_in = exact.size();
  r.vertices_out = kept.size();
  return r;
}

PrincipalFrame principal_frame(const std::vector<Triangle>& triangles) {
  PrincipalFrame f;
  // Sums relative to a point of the surface, which keeps them accurate far from the origin.
  const Vec3 o = triangles.empty() ? Vec3::Zero() : triangles[0][0];
  double v6 = 0.0;
  Vec3 m24 = Vec3::Zero();
  Mat3 c120 = Mat3::Zero();
  for (const Triangle& t : triangles) {
    const Vec3 a = t[0] - o, b = t[1] - o, c = t[2] - o;
    const double det = a.dot(b.cross(c));
    const Vec3 s = a + b + c;
    v6 += det;
    m24 += det * s;
    c120 += det * (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
  }
  if (!(std::abs(v6) > 0.0)) throw std::invalid_argument("the surface encloses no volume");
  // An inward-oriented surface gives every sum the opposite sign; their ratios are the same.
  f.volume_m3 = std::abs(v6) / 6.0;
  const Vec3 centroid_rel = (m24 / 24.0) / (v6 / 6.0);
  const Mat3 second_rel = (c120 / 120.0) * (v6 > 0.0 ? 1.0 : -1.0);
  const Mat3 central = second_rel - f.volume_m3 * centroid_rel * centroid_rel.transpose();
  f.centroid_m = o + centroid_rel;
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(0.5 * (central + central.transpose()));
  // Eigen sorts increasing: the length axis has the largest second moment.
  for (int k = 0; k < 3; ++k) {
    f.axes.col(k) = eig.eigenvectors().col(2 - k);
    f.second_moments_m5[k] = eig.eigenvalues()[2 - k];
  }
  // Each of the first two axes towards the side the surface reaches farther; the third completes
  // a right-handed frame.
  for (int k = 0; k < 2; ++k) {
    double lo = 0.0, hi = 0.0;
    for (const Triangle& t : triangles)
      for (const Vec3& p : t) {
        const double x = (p - f.centroid_m).dot(f.axes.col(k));
        lo = std::min(lo, x);
        hi = std::max(hi, x);
      }
    if (-lo > hi) f.axes.col(k) *= -1.0;
  }
  f.axes.col(2) = f.axes.col(0).cross(f.axes.col(1));
  return f;
}

std::vector<Triangle> to_frame(const std::vector<Triangle>& triangles, const PrincipalFrame& f) {
  std::vector<Triangle> out;
  out.reserve(triangles.size());
  const Mat3 rt = f.axes.transpose();
  for (const Triangle& t : triangles) out.push_back({rt * (t[0] - f.centroid_m), rt * (t[1] - f.centroid_m), rt * (t[2] - f.centroid_m)});
  return out;
}

}  // namespace seedcal
