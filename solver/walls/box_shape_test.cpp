// Nearest points of rectangles and boxes: faces, edges, corners, inside and outside, and the
// shared-edge rule (one contact per edge or corner). Exact geometry: tolerances are rounding
// (1e-15 m on 0.1 m coordinates is ~10 ulp).
#include <gtest/gtest.h>

#include <cmath>

#include "solver/walls/box_shape.hpp"

namespace seedcal {
namespace {

constexpr double kExact = 1e-15;

// Contacts (primitives kept by nearest()) of a sphere centred at c with radius r.
int contacts(const WallShape& s, const Vec3& c, double r) {
  int n = 0;
  WallHit h;
  for (int p = 0; p < s.primitive_count(); ++p)
    if (s.nearest(p, c, r, h) && h.distance < r) ++n;
  return n;
}

TEST(BoxShape, InsideFacesAndOpenTopRim) {
  const BoxShape b(Vec3(0.1, 0.1, 0.1), true);
  EXPECT_EQ(b.primitive_count(), 5);
  WallHit h;
  ASSERT_TRUE(b.nearest(0, Vec3(0.05, 0.05, 0.003), 0.005, h));  // floor
  EXPECT_NEAR(h.distance, 0.003, kExact);
  EXPECT_NEAR(h.normal.z(), -1.0, kExact);
  ASSERT_TRUE(b.nearest(1, Vec3(0.002, 0.05, 0.05), 0.005, h));  // x = 0 face
  EXPECT_NEAR(h.normal.x(), -1.0, kExact);
  ASSERT_TRUE(b.nearest(2, Vec3(0.097, 0.05, 0.05), 0.005, h));  // x = lx face
  EXPECT_NEAR(h.normal.x(), 1.0, kExact);
  EXPECT_FALSE(b.nearest(2, Vec3(0.05, 0.05, 0.05), 0.005, h));  // out of reach
  // Above the open top, beside the rim of the x = 0 face: the edge is the nearest point.
  ASSERT_TRUE(b.nearest(1, Vec3(0.002, 0.05, 0.102), 0.005, h));
  EXPECT_NEAR(h.distance, std::hypot(0.002, 0.002), kExact);
  EXPECT_TRUE(h.point.isApprox(Vec3(0.0, 0.05, 0.1), kExact));
  EXPECT_TRUE(h.normal.isApprox(Vec3(-1.0, 0.0, -1.0).normalized(), 1e-12));
  // An inner corner: three faces touch a sphere at three distinct points (three real contacts).
  EXPECT_EQ(contacts(b, Vec3(0.003, 0.003, 0.003), 0.004), 3);
}

TEST(BoxShape, OutsideEdgesAndCornersCountOnce) {
  const BoxShape b(Vec3(0.1, 0.1, 0.1), false, BoxShape::Facing::outside);
  EXPECT_EQ(b.primitive_count(), 6);
  WallHit h;
  // Beside a face: one contact, normal into the box.
  ASSERT_TRUE(b.nearest(1, Vec3(-0.003, 0.05, 0.05), 0.005, h));
  EXPECT_NEAR(h.distance, 0.003, kExact);
  EXPECT_NEAR(h.normal.x(), 1.0, kExact);
  EXPECT_EQ(contacts(b, Vec3(-0.003, 0.05, 0.05), 0.005), 1);
  // Beyond the edge x = 0, z = 0: faces x = 0 and floor both reach the edge point; one contact.
  const Vec3 ce(-0.002, 0.05, -0.002);
  EXPECT_EQ(contacts(b, ce, 0.005), 1);
  ASSERT_TRUE(b.nearest(0, ce, 0.005, h));  // the lower index keeps it
  EXPECT_NEAR(h.distance, std::hypot(0.002, 0.002), kExact);
  EXPECT_TRUE(h.point.isApprox(Vec3(0.0, 0.05, 0.0), kExact));
  EXPECT_TRUE(h.normal.isApprox(Vec3(1.0, 0.0, 1.0).normalized(), 1e-12));
  // Beyond the corner (0, 0, 0): three faces reach it; one contact, normal along the diagonal.
  const Vec3 cc(-0.002, -0.002, -0.002);
  EXPECT_EQ(contacts(b, cc, 0.005), 1);
  ASSERT_TRUE(b.nearest(0, cc, 0.005, h));
  EXPECT_NEAR(h.distance, std::sqrt(3.0) * 0.002, kExact);
  EXPECT_TRUE(h.normal.isApprox(Vec3(1.0, 1.0, 1.0).normalized(), 1e-12));
  // Over a face near an edge: the face is nearer than its neighbour's edge point; one contact.
  EXPECT_EQ(contacts(b, Vec3(-0.003, 0.05, 0.001), 0.005), 1);
  // near() (the contact list's test) still lists the floor, which may own the edge later.
  EXPECT_TRUE(b.near(0, Vec3(-0.003, 0.05, 0.001), 0.005));
}

TEST(Rectangle, FiniteRectangleFaceEdgeCorner) {
  // A 40 x 20 mm plate in the plane z = 0, tilted frame axes.
  const BoxShape plate({Rectangle::make(Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), 0.02, 0.01)});
  WallHit h;
  ASSERT_TRUE(plate.nearest(0, Vec3(0.005, 0.005, 0.002), 0.003, h));  // over the face
  EXPECT_NEAR(h.distance, 0.002, kExact);
  EXPECT_NEAR(h.normal.z(), -1.0, kExact);
  ASSERT_TRUE(plate.nearest(0, Vec3(0.005, 0.005, -0.002), 0.003, h));  // under it (thin shell)
  EXPECT_NEAR(h.normal.z(), 1.0, kExact);
  ASSERT_TRUE(plate.nearest(0, Vec3(0.022, 0.0, 0.001), 0.003, h));  // beyond the edge x = 20 mm
  EXPECT_TRUE(h.point.isApprox(Vec3(0.02, 0.0, 0.0), kExact));
  EXPECT_NEAR(h.distance, std::hypot(0.002, 0.001), kExact);
  ASSERT_TRUE(plate.nearest(0, Vec3(0.021, 0.011, 0.001), 0.003, h));  // beyond the corner
  EXPECT_TRUE(h.point.isApprox(Vec3(0.02, 0.01, 0.0), kExact));
  EXPECT_NEAR(h.distance, std::sqrt(3.0) * 0.001, kExact);
  EXPECT_FALSE(plate.nearest(0, Vec3(0.025, 0.0, 0.0), 0.003, h));  // beyond reach of the edge
  EXPECT_THROW(Rectangle::make(Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), 0.0, 0.01), std::invalid_argument);
}

}  // namespace
}  // namespace seedcal
