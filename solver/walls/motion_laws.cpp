#include "solver/walls/motion_laws.hpp"

#include <algorithm>
#include <cmath>

namespace seedcal {

void ConstantVelocity::advance(Wall& w, double, double dt) {
  w.pose.velocity_m_s = v_;
  w.pose.origin_m += dt * v_;
}

Rotation::Rotation(const Vec3& axis, const Vec3& point_m, double rate_rad_s, const WallPose& start)
    : axis_(axis.normalized()), point_(point_m), rate_(rate_rad_s), start_(start) {}

void Rotation::advance(Wall& w, double t, double dt) {
  const double angle = rate_ * (t + dt);
  const Quat r(Eigen::AngleAxisd(angle, axis_));
  w.pose.orientation = (r * start_.orientation).normalized();
  w.pose.origin_m = point_ + r * (start_.origin_m - point_);
  w.pose.angular_velocity_rad_s = rate_ * axis_;
  w.pose.velocity_m_s = w.pose.angular_velocity_rad_s.cross(w.pose.origin_m - point_);
}

void Schedule::advance(Wall& w, double t, double dt) {
  // Displacement over [t, t + dt]: integral of the piecewise-constant velocity.
  Vec3 disp = Vec3::Zero(), v_now = Vec3::Zero();
  for (const Segment& s : segments_) {
    const double a = std::max(t, s.t_start_s), b = std::min(t + dt, s.t_end_s);
    if (b > a) disp += (b - a) * s.velocity_m_s;
    if (t + dt > s.t_start_s && t + dt <= s.t_end_s) v_now = s.velocity_m_s;
  }
  w.pose.origin_m += disp;
  w.pose.velocity_m_s = v_now;
}

double Schedule::max_speed_m_s(double) const {
  double v = 0.0;
  for (const Segment& s : segments_) v = std::max(v, s.velocity_m_s.norm());
  return v;
}

Servo::Servo(const Vec3& direction, double target_force_n, double max_speed_m_s, double alpha)
    : dir_(direction.normalized()), target_(target_force_n), v_max_(max_speed_m_s), alpha_(alpha) {}

void Servo::advance(Wall& w, double, double dt) {
  const double error = target_ - measured_force_n(w);
  double v = w.contact_stiffness_n_m > 0.0 ? alpha_ * error / (w.contact_stiffness_n_m * dt) : v_max_;
  v = std::clamp(v, -v_max_, v_max_);
  w.pose.velocity_m_s = v * dir_ + transverse_;
  w.pose.origin_m += dt * w.pose.velocity_m_s;
}

}  // namespace seedcal
