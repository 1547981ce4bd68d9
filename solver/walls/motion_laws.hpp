#pragma once
// Prescribed wall motions (DESIGN.md: "prescribed motion is a law attached to a wall").
#include <vector>

#include "solver/walls/servo_wall.hpp"  // the servo law, kept beside these for existing users
#include "solver/walls/wall.hpp"

namespace seedcal {

// Translation at a constant velocity.
class ConstantVelocity final : public WallMotion {
 public:
  explicit ConstantVelocity(const Vec3& v) : v_(v) {}
  void advance(Wall& w, double t, double dt) override;
  double max_speed_m_s(double) const override { return v_.norm(); }

 private:
  Vec3 v_;
};

// Rotation about a fixed axis through `point` at `rate_rad_s` (the drum), starting from the pose
// `start` at time `t_start_s`. The pose is computed from the elapsed time, not accumulated: the
// turn R(angle) = AngleAxis(rate (t - t_start), axis) is composed with the start orientation,
// q = R q_start, and the origin turned about the point, o = point + R (o_start - point), so it
// does not drift. Velocity of the wall's origin: w x (o - point).
class Rotation final : public WallMotion {
 public:
  Rotation(const Vec3& axis, const Vec3& point_m, double rate_rad_s, const WallPose& start,
           double t_start_s = 0.0);
  void advance(Wall& w, double t, double dt) override;
  double max_speed_m_s(double extent_m) const override { return std::abs(rate_) * extent_m; }
  static double rpm_to_rad_s(double rpm) { return rpm * 2.0 * 3.14159265358979323846 / 60.0; }

 private:
  Vec3 axis_, point_;
  double rate_;
  WallPose start_;
  double t_start_;
};

// Piecewise-constant velocity: segment k moves at velocity[k] from t_start[k] to t_end[k]; at rest
// outside the segments (e.g. lift a piling cylinder after the fill has settled).
class Schedule final : public WallMotion {
 public:
  struct Segment {
    double t_start_s, t_end_s;
    Vec3 velocity_m_s;
  };
  explicit Schedule(std::vector<Segment> segments) : segments_(std::move(segments)) {}
  void advance(Wall& w, double t, double dt) override;
  double max_speed_m_s(double) const override;
  void append(const Segment& s) { segments_.push_back(s); }

 private:
  std::vector<Segment> segments_;
};

// Piecewise-linear velocity against time: knots (t_k, v_k), t_k increasing, the velocity linear
// between neighbouring knots and zero before the first and after the last (so a profile that is
// to stop ends with a zero knot). The displacement over a step is the exact integral (trapezoids
// of the interpolated end values), so the pose after any number of steps is exact up to rounding.
class PiecewiseLinearVelocity final : public WallMotion {
 public:
  struct Knot {
    double t_s;
    Vec3 velocity_m_s;
  };
  explicit PiecewiseLinearVelocity(std::vector<Knot> knots);
  // Move `distance_m` along the unit `direction` at `speed_m_s`, starting at `t0_s`, with linear
  // ramps of `ramp_s` up and down (0: a jump), e.g. lift a piling tube after the fill settled.
  static PiecewiseLinearVelocity move(double t0_s, const Vec3& direction, double speed_m_s,
                                      double distance_m, double ramp_s);
  void advance(Wall& w, double t, double dt) override;
  double max_speed_m_s(double) const override;
  Vec3 velocity_at(double t_s) const;
  // Displacement from t = -infinity to t_s.
  Vec3 displacement_until(double t_s) const;

 private:
  std::vector<Knot> knots_;
};

}  // namespace seedcal
