// The normal elastic slot (normal_elastic.hpp) on one contact: Hertz's force and its stiffness
// against their closed forms, and four lanes against one.
#include "solver/contact/normal_elastic.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "solver/contact/lanes_test_support.hpp"

namespace seedcal::lanes {
namespace {

using testing::Generic4Ops;

// Two 4.35 mm seeds of E 1.65e8 Pa, nu 0.4 (Table 6): E* = E / (2 (1 - nu^2)), R* = r / 2.
constexpr double kEStar = 1.65e8 / (2.0 * (1.0 - 0.4 * 0.4));
constexpr double kRStar = 0.5 * 4.35e-3;

TEST(NormalElastic, HertzForceAndStiffness) {
  for (const double d : {1e-9, 1e-6, 4.35e-5, 4.35e-4}) {
    const HertzNormal<double> h = hertz_normal<ScalarOps>(kEStar, kRStar, d);
    // Fn = 4/3 E* sqrt(R*) d^1.5 and Sn = 2 E* sqrt(R* d), to a few roundings.
    EXPECT_NEAR(h.force_n, 4.0 / 3.0 * kEStar * std::sqrt(kRStar) * std::pow(d, 1.5),
                1e-14 * h.force_n);
    EXPECT_NEAR(h.stiffness_n_m, 2.0 * kEStar * std::sqrt(kRStar * d), 1e-14 * h.stiffness_n_m);
    // Sn is dFn/dd: a central difference over 1e-4 d has a truncation error of order
    // (1e-4)^2 / 24 relative, and a rounding error of order 1e-16 / 1e-4.
    const double e = 1e-4 * d;
    const double dfdd = (hertz_normal<ScalarOps>(kEStar, kRStar, d + e).force_n -
                         hertz_normal<ScalarOps>(kEStar, kRStar, d - e).force_n) /
                        (2.0 * e);
    EXPECT_NEAR(dfdd, h.stiffness_n_m, 1e-9 * h.stiffness_n_m);
  }
}

TEST(NormalElastic, NoOverlapNoForce) {
  const HertzNormal<double> h = hertz_normal<ScalarOps>(kEStar, kRStar, 0.0);
  EXPECT_EQ(h.force_n, 0.0);
  EXPECT_EQ(h.stiffness_n_m, 0.0);
}

// The force of a sphere on a wall (R* = r) equals that of two spheres of twice the radius.
TEST(NormalElastic, WallIsASphereOfInfiniteRadius) {
  const double d = 1e-5;
  EXPECT_EQ(hertz_normal<ScalarOps>(kEStar, 4.35e-3, d).force_n,
            hertz_normal<ScalarOps>(kEStar, 0.5 * 8.7e-3, d).force_n);
}

TEST(NormalElastic, FourLanesGiveTheBitsOfOne) {
  const double d[4] = {1e-9, 3e-7, 2e-5, 4e-4};
  const HertzNormal<testing::G4> h4 = hertz_normal<Generic4Ops>(
      Generic4Ops::splat(kEStar), Generic4Ops::splat(kRStar), testing::lanes4(d[0], d[1], d[2], d[3]));
  for (int l = 0; l < 4; ++l) {
    const HertzNormal<double> h = hertz_normal<ScalarOps>(kEStar, kRStar, d[l]);
    EXPECT_TRUE(testing::same_bits(h4.force_n[l], h.force_n)) << l;
    EXPECT_TRUE(testing::same_bits(h4.stiffness_n_m[l], h.stiffness_n_m)) << l;
  }
}

}  // namespace
}  // namespace seedcal::lanes
