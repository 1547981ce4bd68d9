// Nearest points of finite cylinders: inside and outside, lateral surface, caps, rims; one contact
// per rim; the symmetry axis. Exact geometry: tolerances are rounding (1e-15 m).
#include <gtest/gtest.h>

#include <cmath>

#include "solver/walls/cylinder_shape.hpp"

namespace seedcal {
namespace {

constexpr double kExact = 1e-15;

int contacts(const WallShape& s, const Vec3& c, double r) {
  int n = 0;
  WallHit h;
  for (int p = 0; p < s.primitive_count(); ++p)
    if (s.nearest(p, c, r, h) && h.distance < r) ++n;
  return n;
}

TEST(CylinderShape, InsideSideCapsAndRim) {
  const CylinderShape c(0.1, 0.05, true, true, true);
  WallHit h;
  ASSERT_TRUE(c.nearest(0, Vec3(0.095, 0.0, 0.02), 0.01, h));
  EXPECT_NEAR(h.distance, 0.005, kExact);
  EXPECT_NEAR(h.normal.x(), 1.0, kExact);  // from the centre towards the wall
  EXPECT_FALSE(c.nearest(0, Vec3(0.05, 0.0, 0.02), 0.01, h));
  // Off-axis direction: the nearest side point is along the radial direction.
  ASSERT_TRUE(c.nearest(0, Vec3(0.06, 0.06, 0.02), 0.02, h));
  EXPECT_NEAR(h.distance, 0.1 - std::hypot(0.06, 0.06), kExact);
  EXPECT_TRUE(h.point.isApprox(Vec3(0.1 / std::sqrt(2.0), 0.1 / std::sqrt(2.0), 0.02), kExact));
  ASSERT_TRUE(c.nearest(1, Vec3(0.0, 0.02, 0.004), 0.01, h));  // bottom cap
  EXPECT_NEAR(h.distance, 0.004, kExact);
  EXPECT_NEAR(h.normal.z(), -1.0, kExact);
  ASSERT_TRUE(c.nearest(2, Vec3(0.0, 0.0, 0.047), 0.01, h));  // top cap
  EXPECT_NEAR(h.normal.z(), 1.0, kExact);
  // The inner corner of a drum: side and cap touch at two distinct points (two real contacts).
  EXPECT_EQ(contacts(c, Vec3(0.097, 0.0, 0.003), 0.004), 2);
  // Below an open tube's lower rim: the nearest point is on the rim circle.
  const CylinderShape tube(0.02, 0.1, true, false, false);
  ASSERT_TRUE(tube.nearest(0, Vec3(0.018, 0.0, -0.002), 0.005, h));
  EXPECT_NEAR(h.distance, std::hypot(0.002, 0.002), kExact);
  EXPECT_FALSE(tube.nearest(1, Vec3(0.0, 0.0, -0.001), 0.005, h));  // no cap
  EXPECT_EQ(tube.symmetry_axis(), Vec3::UnitZ());
}

TEST(CylinderShape, OutsideSideCapsAndOneContactPerRim) {
  const CylinderShape c(0.02, 0.05, false, true, true);
  WallHit h;
  ASSERT_TRUE(c.nearest(0, Vec3(0.0, 0.023, 0.01), 0.005, h));  // outside the side
  EXPECT_NEAR(h.distance, 0.003, kExact);
  EXPECT_TRUE(h.normal.isApprox(-Vec3::UnitY(), kExact));
  ASSERT_TRUE(c.nearest(2, Vec3(0.005, 0.0, 0.053), 0.005, h));  // above the top cap
  EXPECT_NEAR(h.distance, 0.003, kExact);
  EXPECT_NEAR(h.normal.z(), -1.0, kExact);
  EXPECT_EQ(contacts(c, Vec3(0.005, 0.0, 0.053), 0.005), 1);
  // Beyond the top rim: side and top cap reach the same rim point; one contact (side, index 0).
  const Vec3 cr(0.022, 0.0, 0.052);
  EXPECT_EQ(contacts(c, cr, 0.005), 1);
  ASSERT_TRUE(c.nearest(0, cr, 0.005, h));
  EXPECT_TRUE(h.point.isApprox(Vec3(0.02, 0.0, 0.05), kExact));
  EXPECT_NEAR(h.distance, std::hypot(0.002, 0.002), kExact);
  EXPECT_FALSE(c.nearest(2, cr, 0.005, h));
  EXPECT_TRUE(c.near(2, cr, 0.005));  // still a candidate for the contact list
  // Beside the side just below the top rim: the side's face contact, the cap's rim point is
  // farther, so one contact.
  EXPECT_EQ(contacts(c, Vec3(0.023, 0.0, 0.049), 0.005), 1);
}

}  // namespace
}  // namespace seedcal
