// The normal damping slot (normal_damping.hpp) on one contact: the dashpot against its closed form
// and the damping ratio Tsuji's beta gives; HMNR's scale keeps the damping ratio of n equal
// contacts in parallel at that of one.
#include "solver/contact/normal_damping.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "solver/contact/lanes_test_support.hpp"
#include "solver/core/materials.hpp"

namespace seedcal::lanes {
namespace {

constexpr double kStiffness = 2.4e5;  // N/m, a seed pair at about 20 um of overlap
constexpr double kMass = 2.9e-4;      // kg, half a 0.58 g seed

TEST(NormalDamping, DashpotClosedForm) {
  for (const double e : {0.1, 0.45, 0.9}) {
    const double beta = damping_beta(e);
    const double cn = normal_dashpot<ScalarOps>(beta, 1.0, kStiffness, kMass);
    EXPECT_NEAR(cn, -2.0 * std::sqrt(5.0 / 6.0) * beta * std::sqrt(kStiffness * kMass), 1e-14 * cn);
    EXPECT_GT(cn, 0.0);  // beta < 0 for e < 1: the dashpot opposes the approach
    // The damping ratio zeta = cn / (2 sqrt(Sn m*)) = -sqrt(5/6) beta (Tsuji et al. 1992).
    EXPECT_NEAR(cn / (2.0 * std::sqrt(kStiffness * kMass)), -std::sqrt(5.0 / 6.0) * beta, 1e-14);
  }
  // e = 1: no damping.
  EXPECT_EQ(normal_dashpot<ScalarOps>(damping_beta(1.0), 1.0, kStiffness, kMass), 0.0);
}

TEST(NormalDamping, HmnrScale) {
  EXPECT_EQ(hmnr_damping_scale(0), 1.0);
  EXPECT_EQ(hmnr_damping_scale(1), 1.0);
  EXPECT_EQ(hmnr_damping_scale(4), 0.5);
  EXPECT_NEAR(hmnr_damping_scale(9), 1.0 / 3.0, 1e-16);
}

// n equal contacts in parallel are one spring n k and one dashpot n c on the same mass: with the
// scale 1/sqrt(n) their damping ratio is that of a single contact.
TEST(NormalDamping, HmnrKeepsTheDampingRatioOfOneContact) {
  const double beta = damping_beta(0.45);
  const double zeta_one =
      normal_dashpot<ScalarOps>(beta, 1.0, kStiffness, kMass) / (2.0 * std::sqrt(kStiffness * kMass));
  for (const int n : {2, 3, 5, 9}) {
    const double c = normal_dashpot<ScalarOps>(beta, hmnr_damping_scale(n), kStiffness, kMass);
    const double zeta_n = n * c / (2.0 * std::sqrt(n * kStiffness * kMass));
    EXPECT_NEAR(zeta_n, zeta_one, 1e-14) << n;
    // Unscaled, the ratio grows like sqrt(n).
    const double c1 = normal_dashpot<ScalarOps>(beta, 1.0, kStiffness, kMass);
    EXPECT_NEAR(n * c1 / (2.0 * std::sqrt(n * kStiffness * kMass)), std::sqrt(n) * zeta_one, 1e-14);
  }
}

TEST(NormalDamping, FourLanesGiveTheBitsOfOne) {
  using testing::Generic4Ops;
  const double beta[4] = {damping_beta(0.1), damping_beta(0.45), damping_beta(0.65), damping_beta(0.9)};
  const double scale[4] = {1.0, hmnr_damping_scale(2), hmnr_damping_scale(3), 1.0};
  const double k[4] = {1e3, 2.4e5, 7e6, 3e4};
  const testing::G4 c4 = normal_dashpot<Generic4Ops>(
      testing::lanes4(beta[0], beta[1], beta[2], beta[3]),
      testing::lanes4(scale[0], scale[1], scale[2], scale[3]), testing::lanes4(k[0], k[1], k[2], k[3]),
      Generic4Ops::splat(kMass));
  for (int l = 0; l < 4; ++l)
    EXPECT_TRUE(testing::same_bits(c4[l], normal_dashpot<ScalarOps>(beta[l], scale[l], k[l], kMass)));
}

}  // namespace
}  // namespace seedcal::lanes
