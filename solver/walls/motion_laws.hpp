#pragma once
// Prescribed wall motions (DESIGN.md: "prescribed motion is a law attached to a wall").
#include <vector>

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

// Rotation about a fixed axis through `point` at `rate_rad_s` (the drum). The pose is computed
// from the elapsed time, not accumulated, so it does not drift.
class Rotation final : public WallMotion {
 public:
  Rotation(const Vec3& axis, const Vec3& point_m, double rate_rad_s, const WallPose& start);
  void advance(Wall& w, double t, double dt) override;
  double max_speed_m_s(double extent_m) const override { return std::abs(rate_) * extent_m; }
  static double rpm_to_rad_s(double rpm) { return rpm * 2.0 * 3.14159265358979323846 / 60.0; }

 private:
  Vec3 axis_, point_;
  double rate_;
  WallPose start_;
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

// Servo: moves the wall along `direction` (unit, pointing into the particles) so that the normal
// force the particles exert on it holds `target_force_n` (= target stress x area).
//
// Control law (the stress-controlled wall of PFC, Itasca; Cundall 1988): each step the wall moves
//   v = G (F_target - F_measured),   G = alpha / (k_w dt),
// where k_w is the summed normal contact stiffness of the wall's current contacts (reported by the
// contact kernel): one step removes the fraction alpha of the force error if the contacts behaved
// as springs. alpha = 0.1, not PFC's 0.5: a moving wall also loads its contacts' dashpots (c v), so
// the measured force answers the wall's own speed; at 0.5 that feedback drove a bang-bang limit
// cycle (+-6 N on 251 N, mean 1.3 % low) in solver/walls/walls_test.cpp, at 0.1 the lid holds
// 200 kPa to 1e-6. The speed is capped at `max_speed_m_s` so the wall never outruns its contacts
// (quasi-static loading), and with no contacts the wall approaches at the cap.
class Servo final : public WallMotion {
 public:
  Servo(const Vec3& direction, double target_force_n, double max_speed_m_s, double alpha = 0.1);
  void advance(Wall& w, double t, double dt) override;
  double max_speed_m_s(double) const override { return v_max_; }
  void set_target_force(double f) { target_ = f; }
  // A velocity across the servo direction added to the servo motion (a shear-box lid that travels
  // with the upper half).
  void set_transverse_velocity(const Vec3& v) { transverse_ = v - v.dot(dir_) * dir_; }
  double target_force_n() const { return target_; }
  double measured_force_n(const Wall& w) const { return -w.force_n.dot(dir_); }

 private:
  Vec3 dir_;
  double target_, v_max_, alpha_;
  Vec3 transverse_ = Vec3::Zero();
};

}  // namespace seedcal
