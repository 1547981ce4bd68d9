// The CDT rolling slot on one contact (rolling_cdt.hpp: each contact's share of its body's
// capacity) and on one body (rolling_cdt_torque.hpp: the torque from the capacity, static at rest).
#include "solver/contact/rolling_cdt.hpp"

#include <gtest/gtest.h>

#include "solver/contact/lanes_test_support.hpp"
#include "solver/contact/rolling_cdt_torque.hpp"

namespace seedcal {
namespace {

TEST(RollingCdt, CapacityIsMuRTimesNormalForceTimesLever) {
  for (const double fn : {12.0, -0.25}) {  // |Fn|: also in the attractive tail
    const double per_lever = lanes::cdt_capacity_per_lever<lanes::ScalarOps>(0.05, fn);
    EXPECT_DOUBLE_EQ(per_lever * 4.3e-3, 0.05 * std::abs(fn) * 4.3e-3);
  }
  EXPECT_EQ(lanes::cdt_capacity_per_lever<lanes::ScalarOps>(0.0, 12.0), 0.0);
}

TEST(RollingCdt, FourLanesGiveTheBitsOfOne) {
  const double mu[4] = {0.02, 0.05, 0.12, 0.0}, fn[4] = {1.0, -3.0, 16.0, 5.0};
  const lanes::testing::G4 c4 = lanes::cdt_capacity_per_lever<lanes::testing::Generic4Ops>(
      lanes::testing::lanes4(mu[0], mu[1], mu[2], mu[3]),
      lanes::testing::lanes4(fn[0], fn[1], fn[2], fn[3]));
  for (int l = 0; l < 4; ++l)
    EXPECT_TRUE(lanes::testing::same_bits(
        c4[l], lanes::cdt_capacity_per_lever<lanes::ScalarOps>(mu[l], fn[l])))
        << l;
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
