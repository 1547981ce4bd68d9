// The tangential slot (tangential_spring.hpp) on one contact: the spring's increment and force
// while sticking, its turn into a new tangent plane with its length kept, and Coulomb's limit with
// the spring reset to carry it; four lanes against one.
#include "solver/contact/tangential_spring.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "solver/contact/lanes_test_support.hpp"

namespace seedcal::lanes {
namespace {

using testing::norm;

constexpr double kSn = 2.4e5;       // N/m
constexpr double kCn = 3.0;         // N s/m
constexpr double kRatio = 0.85;     // sqrt(St / Sn): sqrt(4 G* / E*) for nu = 0.4
constexpr double kDt = 5e-6;        // s

TangentialIn<double> contact(const V3<double>& v, double mu, double fn) {
  const V3<double> n{0.0, 0.0, 1.0};
  const V3<double> vt = v - dot(v, n) * n;
  return {n, v, vt, kSn, kCn, kRatio, mu, fn};
}

TEST(TangentialSpring, StickingSpringAndDashpot) {
  // Slip of 1 mm/s along x with an approach along the normal, which the spring must not see.
  const V3<double> v{1e-3, 0.0, -0.2};
  const TangentialIn<double> in = contact(v, 0.5, 10.0);
  V3<double> t{0.0, 0.0, 0.0};
  const V3<double> ft = mindlin_tangential<ScalarOps>(in, t, kDt);
  const double st = kSn * kRatio * kRatio, ct = kCn * kRatio;
  EXPECT_DOUBLE_EQ(t.x, 1e-3 * kDt);  // t = vt dt
  EXPECT_EQ(t.y, 0.0);
  EXPECT_EQ(t.z, 0.0);
  EXPECT_DOUBLE_EQ(ft.x, -st * 1e-3 * kDt - ct * 1e-3);  // Ft = -St t - ct vt
  EXPECT_EQ(ft.y, 0.0);
  EXPECT_EQ(ft.z, 0.0);
  // A second step adds the same increment.
  mindlin_tangential<ScalarOps>(in, t, kDt);
  EXPECT_DOUBLE_EQ(t.x, 2e-3 * kDt);
}

// A spring left in the old tangent plane is turned into the new one with its length kept.
TEST(TangentialSpring, TurnsWithTheContactKeepingItsLength) {
  const double a = 0.3;  // the normal tilted by 0.3 rad about y
  TangentialIn<double> in = contact({0.0, 0.0, 0.0}, 0.5, 10.0);
  in.normal = {std::sin(a), 0.0, std::cos(a)};
  in.v_rel_t_end_m_s = {0.0, 0.0, 0.0};
  V3<double> t{2e-6, 1e-6, 0.0};
  const double len0 = norm(t);
  const V3<double> ft = mindlin_tangential<ScalarOps>(in, t, kDt);
  // To a few roundings of the projection and the rescaling: 4 machine epsilons of the length.
  const double eps = 4.0 * std::numeric_limits<double>::epsilon() * len0;
  EXPECT_NEAR(dot(t, in.normal), 0.0, eps);
  EXPECT_NEAR(norm(t), len0, eps);
  EXPECT_NEAR(norm(ft), kSn * kRatio * kRatio * len0, 1e-12 * norm(ft));
}

TEST(TangentialSpring, SlidingIsCappedAtCoulombAndTheSpringCarriesTheLimit) {
  const double mu = 0.3, fn = 10.0;
  for (const double fn_sign : {1.0, -1.0}) {  // |Fn|: also in the attractive tail
    const TangentialIn<double> in = contact({0.5, -0.2, 0.0}, mu, fn_sign * fn);
    V3<double> t{1e-4, 0.0, 0.0};
    const V3<double> ft = mindlin_tangential<ScalarOps>(in, t, kDt);
    EXPECT_NEAR(norm(ft), mu * fn, 1e-14 * mu * fn);
    // The force opposes the spring's direction, the slip's history; the spring alone carries it.
    const double st = kSn * kRatio * kRatio;
    EXPECT_NEAR(-st * t.x, ft.x, 1e-14 * mu * fn);
    EXPECT_NEAR(-st * t.y, ft.y, 1e-14 * mu * fn);
    EXPECT_EQ(t.z, 0.0);
  }
  // No friction: no tangential force, no spring.
  const TangentialIn<double> in = contact({0.5, 0.0, 0.0}, 0.0, fn);
  V3<double> t{1e-6, 0.0, 0.0};
  const V3<double> ft = mindlin_tangential<ScalarOps>(in, t, kDt);
  EXPECT_EQ(norm(ft), 0.0);
  EXPECT_EQ(norm(t), 0.0);
}

TEST(TangentialSpring, FourLanesGiveTheBitsOfOne) {
  using testing::G4;
  using testing::Generic4Ops;
  // Lanes 0 and 1 stick, 2 slides, 3 turns its spring.
  const V3<double> v[4] = {{1e-3, 0, -0.1}, {0, 2e-4, 0}, {0.7, 0.4, 0}, {1e-4, 1e-4, 0}};
  const V3<double> n[4] = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {std::sin(0.2), 0, std::cos(0.2)}};
  const V3<double> t0[4] = {{0, 0, 0}, {1e-7, 0, 0}, {1e-5, 0, 0}, {3e-6, 1e-6, 0}};
  const double fn[4] = {10.0, 3.0, 8.0, -0.5};
  TangentialIn<G4> in4;
  in4.normal = testing::lanes4(n[0], n[1], n[2], n[3]);
  in4.v_rel_m_s = testing::lanes4(v[0], v[1], v[2], v[3]);
  V3<double> vt[4];
  for (int l = 0; l < 4; ++l) vt[l] = v[l] - dot(v[l], n[l]) * n[l];
  in4.v_rel_t_end_m_s = testing::lanes4(vt[0], vt[1], vt[2], vt[3]);
  in4.normal_stiffness_n_m = Generic4Ops::splat(kSn);
  in4.normal_dashpot = Generic4Ops::splat(kCn);
  in4.sqrt_tangential_ratio = Generic4Ops::splat(kRatio);
  in4.static_friction = Generic4Ops::splat(0.5);
  in4.normal_force_n = testing::lanes4(fn[0], fn[1], fn[2], fn[3]);
  V3<G4> t4 = testing::lanes4(t0[0], t0[1], t0[2], t0[3]);
  const V3<G4> ft4 = mindlin_tangential<Generic4Ops>(in4, t4, kDt);
  for (int l = 0; l < 4; ++l) {
    const TangentialIn<double> in{n[l], v[l], vt[l], kSn, kCn, kRatio, 0.5, fn[l]};
    V3<double> t = t0[l];
    const V3<double> ft = mindlin_tangential<ScalarOps>(in, t, kDt);
    EXPECT_TRUE(testing::same_bits(testing::lane(ft4, l), ft)) << l;
    EXPECT_TRUE(testing::same_bits(testing::lane(t4, l), t)) << l;
  }
}

}  // namespace
}  // namespace seedcal::lanes
