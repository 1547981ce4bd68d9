// Buried spheres of a clump: wholly inside another (pairwise, exact) or covered by the others
// together (sampled reach), on configurations whose answer follows from the geometry.
#include <gtest/gtest.h>

#include "solver/clump/buried_spheres.hpp"

namespace seedcal {
namespace {

TEST(BuriedSpheres, InsideTangentAndDuplicateAreFoundAndNothingElse) {
  const std::vector<SphereXYZR> s = {
      {Vec3(0, 0, 0), 4.0},       // 0: the big one
      {Vec3(1, 0, 0), 1.0},       // 1: wholly inside 0 (1 + 1 < 4)
      {Vec3(0, 0, 2.25), 1.75},   // 2: tangent inside 0 (2.25 + 1.75 = 4): reaches 0 out
      {Vec3(3.5, 0, 0), 1.0},     // 3: reaches 0.5 out of 0: half its radius
      {Vec3(3.5, 0, 0), 1.0},     // 4: a copy of 3: the later copy is the buried one
      {Vec3(10, 0, 0), 0.5},      // 5: apart
  };
  const auto b = buried_spheres(s, 0.01);
  ASSERT_EQ(b.size(), 3u);
  EXPECT_EQ(b[0].sphere, 1u);
  EXPECT_EQ(b[0].inside, 0u);
  EXPECT_DOUBLE_EQ(b[0].protrusion_fraction, -2.0);  // (1 + 1 - 4) / 1
  EXPECT_EQ(b[1].sphere, 2u);
  EXPECT_NEAR(b[1].protrusion_fraction, 0.0, 1e-15);
  EXPECT_EQ(b[2].sphere, 4u);
  EXPECT_EQ(b[2].inside, 3u);
}

TEST(BuriedSpheres, ToleranceIsAFractionOfTheRadius) {
  // Sphere 1 reaches 0.02 of its radius out of sphere 0: buried at a 5 % tolerance, not at 1 %.
  const std::vector<SphereXYZR> s = {{Vec3(0, 0, 0), 2.0}, {Vec3(1.02, 0, 0), 1.0}};
  EXPECT_NEAR(protrusion_fraction(s[1], s[0]), 0.02, 1e-12);
  EXPECT_TRUE(buried_spheres(s, 0.01).empty());
  ASSERT_EQ(buried_spheres(s, 0.05).size(), 1u);
}

TEST(BuriedSpheres, UnionReachSeesCoverByTwoSpheres) {
  // A unit sphere at the origin between two spheres of radius 1.5 at x = +-0.8: neither holds it
  // (it reaches 0.3 of its radius out of each: 0.8 + 1 - 1.5), but together they cover it: every
  // point of its surface lies inside one of them, so its reach out of their union is negative.
  const std::vector<SphereXYZR> s = {{Vec3(0, 0, 0), 1.0}, {Vec3(0.8, 0, 0), 1.5}, {Vec3(-0.8, 0, 0), 1.5}};
  EXPECT_TRUE(buried_spheres(s, 0.01).empty());
  const auto dirs = fibonacci_directions(2000);
  // The point of the unit sphere farthest from both centres is on the circle x = 0, at distance
  // sqrt(0.8^2 + 1) = 1.2806 from each: 1.2806 - 1.5 = -0.219 of the radius.
  EXPECT_NEAR(union_reach_fraction(s, 0, dirs), std::sqrt(0.64 + 1.0) - 1.5, 2e-3);
  // One sphere alone: the reach is the exact pairwise protrusion, to the lattice's resolution
  // (2000 points: spacing about 0.08 rad, so a cap error below 1 - cos(0.08) = 0.0032).
  const std::vector<SphereXYZR> two = {s[0], s[1]};
  EXPECT_NEAR(union_reach_fraction(two, 0, dirs), protrusion_fraction(s[0], s[1]), 3.2e-3);
}

TEST(BuriedSpheres, FibonacciDirectionsAreUnitAndBalanced) {
  const auto d = fibonacci_directions(1000);
  ASSERT_EQ(d.size(), 1000u);
  Vec3 sum = Vec3::Zero();
  for (const Vec3& u : d) {
    EXPECT_NEAR(u.norm(), 1.0, 1e-12);
    sum += u;
  }
  // The lattice is symmetric to within one point's share: the mean direction is below 1/n.
  EXPECT_LT(sum.norm() / 1000.0, 1e-3);
}

}  // namespace
}  // namespace seedcal
