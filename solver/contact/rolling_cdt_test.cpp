// The CDT rolling slot on one contact (rolling_cdt.hpp: each contact's share of its body's
// capacity) and on one body (rolling_cdt_torque.hpp: the torque from the capacity, static at rest).
#include "solver/contact/rolling_cdt.hpp"

#include <gtest/gtest.h>

#include "solver/contact/lanes_test_support.hpp"
#include "solver/contact/rolling_cdt_torque.hpp"

namespace seedcal {
namespace {

TEST(RollingCdt, CapacityIsMuRTimesNormalForceTimesLever) {
  const double levers[2] = {4.3e-3, 6.1e-3};
  for (const double fn : {12.0, -0.25}) {  // |Fn|: also in the attractive tail
    double c[2];
    lanes::cdt_capacity<lanes::ScalarOps, 2>(0.05, fn, levers, c);
    EXPECT_DOUBLE_EQ(c[0], 0.05 * std::abs(fn) * 4.3e-3);
    EXPECT_DOUBLE_EQ(c[1], 0.05 * std::abs(fn) * 6.1e-3);
  }
  const double one[1] = {4.3e-3};
  double c[1];
  lanes::cdt_capacity<lanes::ScalarOps, 1>(0.0, 12.0, one, c);
  EXPECT_EQ(c[0], 0.0);
}

TEST(RollingCdt, FourLanesGiveTheBitsOfOne) {
  using lanes::testing::G4;
  const double mu[4] = {0.02, 0.05, 0.12, 0.0}, fn[4] = {1.0, -3.0, 16.0, 5.0},
               lever[4] = {1e-3, 4e-3, 6e-3, 2e-3};
  const G4 levers4[1] = {lanes::testing::lanes4(lever[0], lever[1], lever[2], lever[3])};
  G4 c4[1];
  lanes::cdt_capacity<lanes::testing::Generic4Ops, 1>(
      lanes::testing::lanes4(mu[0], mu[1], mu[2], mu[3]),
      lanes::testing::lanes4(fn[0], fn[1], fn[2], fn[3]), levers4, c4);
  for (int l = 0; l < 4; ++l) {
    const double levers[1] = {lever[l]};
    double c[1];
    lanes::cdt_capacity<lanes::ScalarOps, 1>(mu[l], fn[l], levers, c);
    EXPECT_TRUE(lanes::testing::same_bits(c4[0][l], c[0])) << l;
  }
}

// A body the capacity can stop within the step is stopped exactly: L + h (T + tau) = 0.
TEST(RollingCdt, StaticAtRestStopsTheBody) {
  const Vec3 L(2e-9, -1e-9, 0.5e-9);  // kg m2/s
  const Vec3 T(1e-5, 0.0, 0.0);       // N m
  const double h = 5e-6, capacity = 1e-2;
  const Vec3 tau = capacity * cdt_stop_limited(L, T, capacity, h);
  EXPECT_NEAR((L + h * (T + tau)).norm(), 0.0, 1e-22);
  EXPECT_LT(tau.norm(), capacity);
}

// A body it cannot stop gets the full capacity against L + h T (the literal CDT for a sphere).
TEST(RollingCdt, SpinningBodyGetsTheFullCapacity) {
  const Vec3 L(2e-3, 0.0, 0.0), T(0.0, 0.0, 0.0);
  const double h = 5e-6, capacity = 1e-3;
  const Vec3 tau = capacity * cdt_stop_limited(L, T, capacity, h);
  EXPECT_NEAR(tau.x(), -capacity, 1e-18);
  EXPECT_EQ(tau.y(), 0.0);
  EXPECT_EQ(tau.z(), 0.0);
  EXPECT_EQ(cdt_stop_limited(L, T, 0.0, h), Vec3::Zero());  // no capacity, no torque
  EXPECT_EQ(cdt_stop_limited(Vec3::Zero(), T, capacity, h), Vec3::Zero());
}

TEST(RollingCdt, LiteralDirectionOpposesTheSpin) {
  const Vec3 u = cdt_sign_direction(Vec3(0.0, 3.0, 4.0));
  EXPECT_DOUBLE_EQ(u.y(), -0.6);  // to 4 ulps: a norm and a division
  EXPECT_DOUBLE_EQ(u.z(), -0.8);
  EXPECT_EQ(cdt_sign_direction(Vec3::Zero()), Vec3::Zero());
}

}  // namespace
}  // namespace seedcal
