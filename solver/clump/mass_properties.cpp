#include "solver/clump/mass_properties.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <Eigen/Eigenvalues>

namespace seedcal {
namespace {

// Moments of a region: volume, first moments, second moments (for density 1, about the origin).
struct Moments {
  double v = 0.0;
  Vec3 s = Vec3::Zero();   // int x dV
  Mat3 xx = Mat3::Zero();  // int x x^T dV
  void add_box(const Vec3& c, double h) {  // cube of half-edge h centred at c
    const double vol = 8.0 * h * h * h;
    v += vol;
    s += vol * c;
    xx += vol * (c * c.transpose());
    xx.diagonal().array() += vol * h * h / 3.0;  // int (x - c)^2 over [-h, h] / (2h) = h^2/3
  }
  void add(const Moments& o) { v += o.v; s += o.s; xx += o.xx; }
};

struct Octree {
  const std::vector<SphereXYZR>& spheres;
  int max_depth;
  int samples;  // per axis in a partial leaf
  Moments m;

  void cell(const Vec3& c, double h, int depth, const std::vector<std::uint32_t>& cand) {
    std::vector<std::uint32_t> touching;
    touching.reserve(cand.size());
    for (std::uint32_t k : cand) {
      const SphereXYZR& sp = spheres[k];
      const Vec3 d = (sp.centre_m - c).cwiseAbs();
      // Farthest corner distance <= r: the cell lies inside this sphere, so inside the union.
      const Vec3 far = d + Vec3::Constant(h);
      if (far.squaredNorm() <= sp.radius_m * sp.radius_m) { m.add_box(c, h); return; }
      // Nearest point of the cell farther than r: this sphere misses the cell.
      const Vec3 near = (d - Vec3::Constant(h)).cwiseMax(0.0);
      if (near.squaredNorm() < sp.radius_m * sp.radius_m) touching.push_back(k);
    }
    if (touching.empty()) return;
    if (depth == max_depth) {
      // Partial leaf: midpoint rule on a samples^3 grid.
      const double sh = h / samples;
      for (int i = 0; i < samples; ++i)
        for (int j = 0; j < samples; ++j)
          for (int l = 0; l < samples; ++l) {
            const Vec3 p = c + Vec3(-h + (2 * i + 1) * sh, -h + (2 * j + 1) * sh, -h + (2 * l + 1) * sh);
            for (std::uint32_t k : touching)
              if ((p - spheres[k].centre_m).squaredNorm() <= spheres[k].radius_m * spheres[k].radius_m) {
                m.add_box(p, sh);
                break;
              }
          }
      return;
    }
    const double q = 0.5 * h;
    for (int o = 0; o < 8; ++o)
      cell(c + Vec3((o & 1) ? q : -q, (o & 2) ? q : -q, (o & 4) ? q : -q), q, depth + 1, touching);
  }
};

Moments integrate(const std::vector<SphereXYZR>& spheres, int depth) {
  Vec3 lo = spheres[0].centre_m, hi = spheres[0].centre_m;
  for (const auto& s : spheres) {
    lo = lo.cwiseMin(s.centre_m - Vec3::Constant(s.radius_m));
    hi = hi.cwiseMax(s.centre_m + Vec3::Constant(s.radius_m));
  }
  const Vec3 c = 0.5 * (lo + hi);
  const double h = 0.5 * (hi - lo).maxCoeff() * (1.0 + 1e-9);
  std::vector<std::uint32_t> all(spheres.size());
  for (std::size_t k = 0; k < spheres.size(); ++k) all[k] = static_cast<std::uint32_t>(k);
  Octree t{spheres, depth, 4, {}};
  t.cell(c, h, 0, all);
  return t.m;
}

}  // namespace

// Union volume and inertia by an adaptive octree: cells wholly inside one sphere (all corners
// inside it) count exactly, cells that no sphere reaches are dropped, and cells still cut by the
// surface at the finest level are integrated with a 4^3 midpoint rule. The depth grows until two
// successive depths agree on the volume to the tolerance; that difference is reported as the error
// estimate (the midpoint-rule error converges at least linearly in the cell size, so it bounds the
// remaining error of the finer level in practice; see solver/clump/mass_properties_test.cpp).
UnionMassProperties union_mass_properties(const std::vector<SphereXYZR>& spheres,
                                          double rel_tolerance) {
  if (spheres.empty()) throw std::invalid_argument("union_mass_properties: no spheres");
  UnionMassProperties out;
  Moments m;
  if (spheres.size() == 1) {
    const double r = spheres[0].radius_m;
    const Vec3 c = spheres[0].centre_m;
    m.v = 4.0 / 3.0 * std::numbers::pi * r * r * r;
    m.s = m.v * c;
    m.xx = m.v * (c * c.transpose()) + Mat3::Identity() * (m.v * r * r / 5.0);
    out.volume_rel_error_bound = 0.0;
  } else {
    Moments prev = integrate(spheres, 4);
    double err = 1.0;
    for (int depth = 5; depth <= 10; ++depth) {
      m = integrate(spheres, depth);
      err = std::abs(m.v - prev.v) / m.v;
      prev = m;
      if (err < rel_tolerance) break;
    }
    out.volume_rel_error_bound = err;
  }
  out.volume_m3 = m.v;
  out.centroid_m = m.s / m.v;
  // Inertia about the centroid: I = tr(C) 1 - C with C = int (x - c)(x - c)^T dV.
  const Mat3 c2 = m.xx - m.v * (out.centroid_m * out.centroid_m.transpose());
  out.inertia_unit_density = Mat3::Identity() * c2.trace() - c2;
  Eigen::SelfAdjointEigenSolver<Mat3> eig(out.inertia_unit_density);
  out.principal_moments_unit_density = eig.eigenvalues();
  out.principal_axes = eig.eigenvectors();
  if (out.principal_axes.determinant() < 0.0) out.principal_axes.col(2) *= -1.0;
  return out;
}

BodyDef clump_body(const std::vector<SphereXYZR>& spheres, double density_kg_m3,
                   std::uint16_t material, const Vec3& frame_origin_m, const Quat& frame_orientation,
                   double rel_tolerance) {
  const UnionMassProperties mp = union_mass_properties(spheres, rel_tolerance);
  BodyDef d;
  d.material = material;
  d.mass_kg = density_kg_m3 * mp.volume_m3;
  d.principal_inertia_kg_m2 = density_kg_m3 * mp.principal_moments_unit_density;
  const Mat3 axes = mp.principal_axes;  // principal -> input frame
  for (const SphereXYZR& s : spheres)
    d.spheres.push_back({axes.transpose() * (s.centre_m - mp.centroid_m), s.radius_m});
  d.orientation = (frame_orientation * Quat(axes)).normalized();
  d.position_m = frame_origin_m + frame_orientation * mp.centroid_m;
  return d;
}

}  // namespace seedcal
