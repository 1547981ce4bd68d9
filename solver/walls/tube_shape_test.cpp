// Nearest points of a solid tube (a shear-box ring of real wall thickness) and of a solid cylinder
// (a loading cap): the bore, the end faces, the edges between them, the outer surface, a centre
// pushed into the solid. Exact geometry: tolerances are rounding (1e-15 m).
#include <gtest/gtest.h>

#include <cmath>

#include "solver/walls/tube_shape.hpp"

namespace seedcal {
namespace {

constexpr double kExact = 1e-15;

TEST(TubeShape, BoreEndFacesAndEdges) {
  const TubeShape ring(0.03, 0.04, 0.01);  // bore 30 mm, wall 10 mm, 10 mm high
  WallHit h;
  // In the bore, level with the ring: the bore face, radially outwards.
  ASSERT_TRUE(ring.nearest(0, Vec3(0.027, 0.0, 0.005), 0.004, h));
  EXPECT_NEAR(h.distance, 0.003, kExact);
  EXPECT_TRUE(h.normal.isApprox(Vec3::UnitX(), kExact));
  EXPECT_TRUE(h.point.isApprox(Vec3(0.03, 0.0, 0.005), kExact));
  EXPECT_FALSE(ring.nearest(0, Vec3(0.02, 0.0, 0.005), 0.004, h));
  // Off-axis direction: still radial.
  ASSERT_TRUE(ring.nearest(0, Vec3(0.02, 0.02, 0.005), 0.003, h));
  EXPECT_NEAR(h.distance, 0.03 - std::hypot(0.02, 0.02), 1e-15);
  // Above the top face, over the wall: the face, straight down (a seed resting on the lower ring's
  // face in the crescent the upper ring uncovers).
  ASSERT_TRUE(ring.nearest(0, Vec3(-0.035, 0.0, 0.012), 0.004, h));
  EXPECT_NEAR(h.distance, 0.002, kExact);
  EXPECT_TRUE(h.normal.isApprox(Vec3(0, 0, -1), kExact));
  // Below the bottom face: straight up.
  ASSERT_TRUE(ring.nearest(0, Vec3(0.0, 0.036, -0.001), 0.004, h));
  EXPECT_TRUE(h.normal.isApprox(Vec3(0, 0, 1), kExact));
  // Beyond the bore edge (inside the bore radius, above the ring): the edge circle, at 45 deg.
  ASSERT_TRUE(ring.nearest(0, Vec3(0.028, 0.0, 0.012), 0.004, h));
  EXPECT_NEAR(h.distance, std::hypot(0.002, 0.002), kExact);
  EXPECT_TRUE(h.point.isApprox(Vec3(0.03, 0.0, 0.01), kExact));
  EXPECT_TRUE(h.normal.isApprox(Vec3(1, 0, -1).normalized(), 1e-12));
  // Outside the ring: the outer surface.
  ASSERT_TRUE(ring.nearest(0, Vec3(0.042, 0.0, 0.005), 0.004, h));
  EXPECT_TRUE(h.normal.isApprox(Vec3(-1, 0, 0), kExact));
}

TEST(TubeShape, NormalTurnsContinuouslyOverTheEdge) {
  // A sphere centre moving on a circle about the bore edge, from level with the bore to above the
  // face: the distance stays the circle's radius and the normal always points at the edge.
  const TubeShape ring(0.03, 0.04, 0.01);
  const double a = 0.002;
  for (int k = 0; k <= 90; ++k) {
    const double t = k * M_PI / 180.0;
    const Vec3 c(0.03 - a * std::cos(t), 0.0, 0.01 + a * std::sin(t));
    WallHit h;
    ASSERT_TRUE(ring.nearest(0, c, 0.003, h)) << k;
    EXPECT_NEAR(h.distance, a, 1e-15) << k;
    if (k > 0 && k < 90) {
      EXPECT_TRUE(h.point.isApprox(Vec3(0.03, 0.0, 0.01), kExact)) << k;
    }
  }
}

TEST(TubeShape, SolidCylinderCap) {
  const TubeShape cap(0.0, 0.03, 0.005);
  WallHit h;
  // Under the cap: its bottom face, straight up, also on the axis.
  ASSERT_TRUE(cap.nearest(0, Vec3(0.0, 0.0, -0.003), 0.004, h));
  EXPECT_NEAR(h.distance, 0.003, kExact);
  EXPECT_TRUE(h.normal.isApprox(Vec3(0, 0, 1), kExact));
  ASSERT_TRUE(cap.nearest(0, Vec3(0.01, -0.02, -0.001), 0.004, h));
  EXPECT_TRUE(h.point.isApprox(Vec3(0.01, -0.02, 0.0), kExact));
  // Beside it: the side.
  ASSERT_TRUE(cap.nearest(0, Vec3(0.0, 0.032, 0.002), 0.004, h));
  EXPECT_TRUE(h.normal.isApprox(Vec3(0, -1, 0), kExact));
}

TEST(TubeShape, CentreInsideTheSolidIsPushedOutThroughTheNearestFace) {
  const TubeShape ring(0.03, 0.04, 0.01);
  WallHit h;
  // 1 mm into the wall from the bore: negative distance, normal into the solid (the contact force,
  // along -normal, pushes the sphere back into the bore).
  ASSERT_TRUE(ring.nearest(0, Vec3(0.031, 0.0, 0.005), 0.004, h));
  EXPECT_NEAR(h.distance, -0.001, 1e-15);
  EXPECT_TRUE(h.normal.isApprox(Vec3::UnitX(), kExact));
  EXPECT_TRUE(h.point.isApprox(Vec3(0.03, 0.0, 0.005), 1e-15));
  // Nearer the top face: out through the top.
  ASSERT_TRUE(ring.nearest(0, Vec3(0.035, 0.0, 0.0095), 0.004, h));
  EXPECT_NEAR(h.distance, -0.0005, 1e-15);
  EXPECT_TRUE(h.normal.isApprox(Vec3(0, 0, -1), kExact));
  // A solid cylinder has no bore: a centre on its axis leaves through the nearer end.
  const TubeShape cap(0.0, 0.03, 0.005);
  ASSERT_TRUE(cap.nearest(0, Vec3(0.0, 0.0, 0.001), 0.004, h));
  EXPECT_NEAR(h.distance, -0.001, 1e-15);
  EXPECT_TRUE(h.normal.isApprox(Vec3(0, 0, 1), kExact));
}

TEST(TubeShape, RefusesAnEmptySolid) {
  EXPECT_THROW(TubeShape(0.03, 0.03, 0.01), std::invalid_argument);
  EXPECT_THROW(TubeShape(0.0, 0.03, 0.0), std::invalid_argument);
  EXPECT_THROW(TubeShape(-0.01, 0.03, 0.01), std::invalid_argument);
}

}  // namespace
}  // namespace seedcal
