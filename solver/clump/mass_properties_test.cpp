// Union mass properties against exact values: the lens formula for two overlapping spheres, an
// exact slice integration of the same union for its centroid and inertia, disjoint spheres by the
// parallel-axis theorem, invariance under translation and rotation, and the error estimate.
#include "solver/clump/mass_properties.hpp"

#include <chrono>
#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

namespace seedcal {
namespace {

constexpr double kPi = std::numbers::pi;

// Exact union of two spheres on the z axis (centres 0 and d, radii R and r, neither inside the
// other): every cross-section is a disk, of sphere 1 below the radical plane z = a and of sphere 2
// above it, so all moments are integrals of polynomials of degree <= 4 in z; 3-point
// Gauss-Legendre is exact for them.
struct ExactTwo {
  double volume, zc, i_axis, i_perp;  // i_* about the centroid, density 1
};

ExactTwo exact_two(double big_r, double r, double d) {
  const double a = (d * d + big_r * big_r - r * r) / (2.0 * d);
  const double gx[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)};
  const double gw[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  double v = 0, sz = 0, szz = 0, srho4 = 0;
  auto piece = [&](double z0, double z1, double zc_sphere, double rad) {
    for (int i = 0; i < 3; ++i) {
      const double z = 0.5 * (z0 + z1) + 0.5 * (z1 - z0) * gx[i];
      const double w = 0.5 * (z1 - z0) * gw[i];
      const double rho2 = rad * rad - (z - zc_sphere) * (z - zc_sphere);
      v += w * kPi * rho2;
      sz += w * kPi * rho2 * z;
      szz += w * kPi * rho2 * z * z;
      srho4 += w * kPi * rho2 * rho2;  // int rho^4 pi dz: int (x^2 + y^2) dA = pi rho^4 / 2
    }
  };
  piece(-big_r, a, 0.0, big_r);
  piece(a, d + r, d, r);
  const double zc = sz / v;
  const double czz = szz - v * zc * zc;
  return {v, zc, 0.5 * srho4, 0.25 * srho4 + czz};
}

// Lens (intersection) volume of two spheres: pi (R + r - d)^2 (d^2 + 2dr - 3r^2 + 2dR + 6rR - 3R^2)
// / (12 d) (e.g. Weisstein, "Sphere-Sphere Intersection", MathWorld).
double lens_volume(double big_r, double r, double d) {
  return kPi * std::pow(big_r + r - d, 2) *
         (d * d + 2 * d * r - 3 * r * r + 2 * d * big_r + 6 * r * big_r - 3 * big_r * big_r) /
         (12.0 * d);
}

double sphere_volume(double r) { return 4.0 / 3.0 * kPi * r * r * r; }

TEST(MassProperties, TwoOverlappingSpheresMatchLensFormulaAndSlices) {
  const double big_r = 3e-3, r = 2e-3, d = 3.5e-3;
  const auto mp = union_mass_properties({{Vec3(0, 0, 0), big_r}, {Vec3(0, 0, d), r}});
  const double v_exact = sphere_volume(big_r) + sphere_volume(r) - lens_volume(big_r, r, d);
  const ExactTwo ex = exact_two(big_r, r, d);
  // The two exact references agree to round-off.
  ASSERT_NEAR(ex.volume / v_exact, 1.0, 1e-12);
  const double ev = std::abs(mp.volume_m3 / v_exact - 1.0);
  // 1e-4: the default tolerance of union_mass_properties.
  EXPECT_LT(ev, 1e-4);
  EXPECT_LE(ev, mp.volume_rel_error_bound) << "the error estimate must not under-state the error";
  // Centroid: off-axis components vanish by symmetry; the axial one within 1e-4 of the size.
  EXPECT_NEAR(mp.centroid_m.x(), 0.0, 1e-4 * big_r);
  EXPECT_NEAR(mp.centroid_m.y(), 0.0, 1e-4 * big_r);
  EXPECT_NEAR(mp.centroid_m.z(), ex.zc, 1e-4 * big_r);
  // Principal moments: the axial one is the smallest here; 3e-4 relative (second moments weight
  // the surface, where the leaf quadrature errs, about twice as much as the volume does).
  const Vec3 pm = mp.principal_moments_unit_density;
  EXPECT_NEAR(pm[0] / ex.i_axis, 1.0, 3e-4);
  EXPECT_NEAR(pm[1] / ex.i_perp, 1.0, 3e-4);
  EXPECT_NEAR(pm[2] / ex.i_perp, 1.0, 3e-4);
  std::printf("two spheres: volume error %.2e (estimate %.2e), inertia errors %.2e %.2e %.2e\n", ev,
              mp.volume_rel_error_bound, pm[0] / ex.i_axis - 1, pm[1] / ex.i_perp - 1,
              pm[2] / ex.i_perp - 1);
}

TEST(MassProperties, ErrorEstimateIsHonestOverManyPairs) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double worst_ratio = 0.0;
  for (int t = 0; t < 40; ++t) {
    const double big_r = 1e-3 * (1.0 + u(rng)), r = 1e-3 * (0.3 + u(rng));
    const double d = (big_r - r) + 1e-6 + (2 * r - 2e-6) * u(rng) * 0.999;  // partial overlap
    const auto mp = union_mass_properties({{Vec3(0, 0, 0), big_r}, {Vec3(0, 0, d), r}}, 1e-3);
    const double v_exact = sphere_volume(big_r) + sphere_volume(r) - lens_volume(big_r, r, d);
    const double ev = std::abs(mp.volume_m3 / v_exact - 1.0);
    worst_ratio = std::max(worst_ratio, ev / mp.volume_rel_error_bound);
    EXPECT_LE(ev, mp.volume_rel_error_bound) << "pair " << t;
    EXPECT_LT(ev, 1e-3);
  }
  std::printf("worst actual/estimated volume error: %.2f\n", worst_ratio);
}

TEST(MassProperties, DisjointSpheresByParallelAxes) {
  const double r1 = 1e-3, r2 = 0.5e-3, sep = 4e-3;
  const auto mp = union_mass_properties({{Vec3(0, 0, 0), r1}, {Vec3(sep, 0, 0), r2}});
  const double v1 = sphere_volume(r1), v2 = sphere_volume(r2), v = v1 + v2;
  const double xc = v2 * sep / v;
  const double i_axis = 0.4 * (v1 * r1 * r1 + v2 * r2 * r2);
  const double i_perp = i_axis + v1 * xc * xc + v2 * (sep - xc) * (sep - xc);
  EXPECT_NEAR(mp.volume_m3 / v, 1.0, 1e-4);
  EXPECT_NEAR(mp.centroid_m.x(), xc, 1e-4 * r1);
  EXPECT_NEAR(mp.principal_moments_unit_density[0] / i_axis, 1.0, 3e-4);
  EXPECT_NEAR(mp.principal_moments_unit_density[2] / i_perp, 1.0, 3e-4);
}

TEST(MassProperties, SingleSphereIsExact) {
  const auto mp = union_mass_properties({{Vec3(1, 2, 3), 2e-3}});
  EXPECT_DOUBLE_EQ(mp.volume_m3, sphere_volume(2e-3));
  EXPECT_EQ(mp.volume_rel_error_bound, 0.0);
  EXPECT_NEAR(mp.principal_moments_unit_density[1], 0.4 * sphere_volume(2e-3) * 4e-6, 1e-20);
}

TEST(MassProperties, SphereInsideAnotherCountsOnce) {
  const auto mp = union_mass_properties({{Vec3(0, 0, 0), 2e-3}, {Vec3(0.5e-3, 0, 0), 1e-3}});
  EXPECT_NEAR(mp.volume_m3 / sphere_volume(2e-3), 1.0, 1e-4);
  EXPECT_NEAR(mp.centroid_m.norm(), 0.0, 1e-4 * 2e-3);
}

// A clump 1 km from the origin and rotated: same volume and principal moments as at the origin
// (the integration runs in a frame centred on the clump, so no digits are lost).
TEST(MassProperties, FarFromOriginAndRotatedGiveTheSameMoments) {
  const std::vector<SphereXYZR> base = {{Vec3(0, 0, 0), 3e-3},
                                        {Vec3(3e-3, 1e-3, 0), 2e-3},
                                        {Vec3(-2.5e-3, 0.5e-3, 1e-3), 1.8e-3},
                                        {Vec3(0.5e-3, -2e-3, 1.5e-3), 1.5e-3}};
  const auto ref = union_mass_properties(base);
  const Quat q = Quat(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized())).normalized();
  const Vec3 shift(1000.0, -500.0, 250.0);
  std::vector<SphereXYZR> moved;
  for (const auto& s : base) moved.push_back({q * s.centre_m + shift, s.radius_m});
  const auto mp = union_mass_properties(moved);
  // 5e-4: both runs carry an error of up to ~2e-4 each (their leaf grids differ once rotated).
  EXPECT_NEAR(mp.volume_m3 / ref.volume_m3, 1.0, 5e-4);
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(mp.principal_moments_unit_density[i] / ref.principal_moments_unit_density[i], 1.0,
                1e-3);
  EXPECT_LT((mp.centroid_m - (q * ref.centroid_m + shift)).norm(), 1e-3 * 3e-3);
}

TEST(MassProperties, ClumpBodyIsInThePrincipalFrame) {
  const std::vector<SphereXYZR> s = {{Vec3(1e-3, 0, 0), 1e-3}, {Vec3(1e-3, 2e-3, 0), 1e-3}};
  const BodyDef b = clump_body(s, 1000.0, 3);
  EXPECT_EQ(b.material, 3);
  ASSERT_EQ(b.spheres.size(), 2u);
  // The centre of mass is at the body origin; the world position is the input-frame centroid.
  EXPECT_LT((b.spheres[0].offset_m + b.spheres[1].offset_m).norm(), 1e-7);
  EXPECT_NEAR(b.position_m.x(), 1e-3, 1e-7);
  EXPECT_NEAR(b.position_m.y(), 1e-3, 1e-7);
  // Rotating body offsets by the orientation gives the input spheres back.
  for (int i = 0; i < 2; ++i)
    EXPECT_LT((b.position_m + b.orientation * b.spheres[i].offset_m - s[i].centre_m).norm(), 1e-9);
}

// Speed: a 2,000-sphere clump (a random dense fill of an ellipsoid) within a couple of seconds.
TEST(MassProperties, TwoThousandSpheresQuickly) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<SphereXYZR> s;
  const Vec3 semi(4.8e-3, 4.5e-3, 4.0e-3);
  while (s.size() < 2000) {
    const Vec3 p(u(rng), u(rng), u(rng));
    if (p.squaredNorm() > 1.0) continue;
    const double depth = 1.0 - p.norm();
    s.push_back({p.cwiseProduct(semi), 0.2e-3 + 3.5e-3 * depth * 0.5});
  }
  const auto t0 = std::chrono::steady_clock::now();
  const auto mp = union_mass_properties(s);
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("2000 spheres: %.3f s, volume %.4e m3, error estimate %.1e\n", secs, mp.volume_m3,
              mp.volume_rel_error_bound);
  EXPECT_LT(mp.volume_rel_error_bound, 1e-3);
  EXPECT_LT(secs, 5.0);  // well above the integration's own time: room for a loaded 2-core machine
}

}  // namespace
}  // namespace seedcal
