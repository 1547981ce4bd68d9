// Motion laws: poses after many steps against the closed-form motion. Tolerances are rounding:
// the rotation is computed from the elapsed time (no accumulation), the translations accumulate
// N additions of dt v, each rounded to half an ulp of the origin (N x 1e-18 m here).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "solver/walls/box_shape.hpp"
#include "solver/walls/cylinder_shape.hpp"
#include "solver/walls/motion_laws.hpp"

namespace seedcal {
namespace {

TEST(MotionLaws, RotationIsExactAfterManySteps) {
  Wall w;
  w.shape = std::make_shared<CylinderShape>(0.1, 0.05, true, true, true);
  w.pose.origin_m = Vec3(0.1, 0.0, 0.0);  // off the axis: the origin itself turns
  Rotation rot(Vec3::UnitY(), Vec3::Zero(), Rotation::rpm_to_rad_s(10.0), w.pose);
  for (int i = 0; i < 100000; ++i) rot.advance(w, i * 1e-5, 1e-5);
  // After 1 s at 10 rpm the wall turned 60 degrees about y.
  const double a = std::numbers::pi / 3.0;
  const Vec3 x = w.pose.orientation * Vec3::UnitX();
  EXPECT_NEAR(x.x(), std::cos(a), 1e-12);
  EXPECT_NEAR(x.z(), -std::sin(a), 1e-12);
  EXPECT_TRUE(w.pose.origin_m.isApprox(Vec3(0.1 * std::cos(a), 0.0, -0.1 * std::sin(a)), 1e-12));
  EXPECT_NEAR(w.pose.angular_velocity_rad_s.y(), std::numbers::pi / 3.0, 1e-12);
  // The origin's velocity is w x (o - point).
  EXPECT_TRUE(w.pose.velocity_m_s.isApprox(w.pose.angular_velocity_rad_s.cross(w.pose.origin_m), 1e-12));
  EXPECT_NEAR(w.pose.orientation.norm(), 1.0, 1e-15);

  // A law started later turns from its start time (no jump).
  Wall v;
  Rotation late(Vec3::UnitZ(), Vec3::Zero(), 2.0, v.pose, 5.0);
  late.advance(v, 5.0, 0.25);
  EXPECT_NEAR(Eigen::AngleAxisd(v.pose.orientation).angle(), 0.5, 1e-15);
}

TEST(MotionLaws, ConstantVelocityAndScheduleAreExact) {
  Wall w;
  ConstantVelocity cv(Vec3(0.01, -0.02, 0.0));
  for (int i = 0; i < 100000; ++i) cv.advance(w, i * 1e-5, 1e-5);
  EXPECT_TRUE(w.pose.origin_m.isApprox(Vec3(0.01, -0.02, 0.0), 1e-12));

  Wall tube;
  Schedule lift({{0.5, 1.5, Vec3(0, 0, 0.01)}});
  for (int i = 0; i < 2000; ++i) lift.advance(tube, i * 1e-3, 1e-3);
  EXPECT_NEAR(tube.pose.origin_m.z(), 0.01, 1e-12);  // 1 s at 10 mm/s
}

TEST(MotionLaws, PiecewiseLinearVelocityIntegratesExactly) {
  // Lift 30 mm at 20 mm/s after 0.1 s, with 0.05 s ramps; a step (0.7 ms) that does not divide
  // the knot times, so steps straddle the ramps' corners.
  const PiecewiseLinearVelocity law = PiecewiseLinearVelocity::move(0.1, Vec3::UnitZ(), 0.02, 0.03, 0.05);
  auto shared = std::make_shared<PiecewiseLinearVelocity>(law);
  Wall w;
  const double dt = 7e-4;
  double t = 0.0;
  double peak = 0.0;
  for (int i = 0; i < 4000; ++i, t += dt) {
    shared->advance(w, t, dt);
    peak = std::max(peak, w.pose.velocity_m_s.z());
    // Mid-ramp: the displacement is the integral of the linear ramp, 0.5 a t^2.
    if (std::abs(t + dt - 0.125) < 0.5 * dt) {
      const double tau = t + dt - 0.1;
      EXPECT_NEAR(w.pose.origin_m.z(), 0.5 * (0.02 / 0.05) * tau * tau, 1e-15);
    }
  }
  EXPECT_NEAR(w.pose.origin_m.z(), 0.03, 1e-15);  // the full distance, then at rest
  EXPECT_EQ(w.pose.velocity_m_s, Vec3::Zero());
  EXPECT_NEAR(peak, 0.02, 1e-15);
  EXPECT_DOUBLE_EQ(shared->max_speed_m_s(1.0), 0.02);
  // Without ramps: still exactly the distance.
  auto jump = std::make_shared<PiecewiseLinearVelocity>(PiecewiseLinearVelocity::move(0.0, Vec3::UnitX(), 0.01, 0.004, 0.0));
  Wall j;
  for (int i = 0; i < 1000; ++i) jump->advance(j, i * 1e-3, 1e-3);
  EXPECT_NEAR(j.pose.origin_m.x(), 0.004, 1e-15);
  EXPECT_THROW(PiecewiseLinearVelocity({{1.0, Vec3::Zero()}, {0.5, Vec3::Zero()}}), std::invalid_argument);
}

TEST(MotionLaws, TurningAboutTheSymmetryAxisMovesNoSurface) {
  // A drum turning about its own axis needs no neighbour-list rebuild; a box turning does.
  const CylinderShape drum(0.1, 0.05, true, true, true);
  const BoxShape box(Vec3::Constant(0.1), false);
  WallPose a, b;
  b.orientation = Quat(Eigen::AngleAxisd(0.3, Vec3::UnitZ()));
  EXPECT_EQ(surface_displacement_m(drum, a, b), 0.0);
  EXPECT_NEAR(surface_displacement_m(box, a, b), 0.3 * box.bounding_radius_m(), 1e-15);
  b.orientation = Quat(Eigen::AngleAxisd(0.3, Vec3::UnitX()));  // across the axis: it moves
  EXPECT_GT(surface_displacement_m(drum, a, b), 0.0);
}

}  // namespace
}  // namespace seedcal
