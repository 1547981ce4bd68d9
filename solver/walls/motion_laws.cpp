#include "solver/walls/motion_laws.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace seedcal {

void ConstantVelocity::advance(Wall& w, double, double dt) {
  w.pose.velocity_m_s = v_;
  w.pose.origin_m += dt * v_;
}

Rotation::Rotation(const Vec3& axis, const Vec3& point_m, double rate_rad_s, const WallPose& start,
                   double t_start_s)
    : axis_(axis.normalized()), point_(point_m), rate_(rate_rad_s), start_(start), t_start_(t_start_s) {
  if (!(axis.norm() > 0.0)) throw std::invalid_argument("Rotation: the axis must be non-zero");
}

void Rotation::advance(Wall& w, double t, double dt) {
  const double angle = rate_ * (t + dt - t_start_);
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

PiecewiseLinearVelocity::PiecewiseLinearVelocity(std::vector<Knot> knots) : knots_(std::move(knots)) {
  if (knots_.empty()) throw std::invalid_argument("PiecewiseLinearVelocity: needs at least one knot");
  for (std::size_t k = 1; k < knots_.size(); ++k)
    if (!(knots_[k].t_s > knots_[k - 1].t_s))
      throw std::invalid_argument("PiecewiseLinearVelocity: knot times must increase");
}

PiecewiseLinearVelocity PiecewiseLinearVelocity::move(double t0, const Vec3& direction, double speed,
                                                      double distance, double ramp) {
  if (!(speed > 0.0) || !(distance > 0.0) || ramp < 0.0)
    throw std::invalid_argument("PiecewiseLinearVelocity::move: speed, distance must be > 0, ramp >= 0");
  const Vec3 v = speed * direction.normalized();
  // With ramps the distance covered is speed (T - ramp) for a plateau ending at T - ramp.
  const double cruise = distance / speed - ramp;  // plateau duration
  if (cruise < 0.0)
    throw std::invalid_argument("PiecewiseLinearVelocity::move: the ramps alone cover more than the distance");
  if (ramp == 0.0) {
    // A jump: knots a hair apart would be ill-conditioned, so use a plateau with steep edges of
    // 1e-9 of the duration (the distance error is zero: the edges are symmetric trapezoids).
    const double e = 1e-9 * distance / speed;
    return PiecewiseLinearVelocity({{t0, Vec3::Zero()}, {t0 + e, v}, {t0 + e + distance / speed - e, v},
                                    {t0 + distance / speed + e, Vec3::Zero()}});
  }
  return PiecewiseLinearVelocity({{t0, Vec3::Zero()}, {t0 + ramp, v}, {t0 + ramp + cruise, v},
                                  {t0 + 2.0 * ramp + cruise, Vec3::Zero()}});
}

Vec3 PiecewiseLinearVelocity::velocity_at(double t) const {
  if (t < knots_.front().t_s || t > knots_.back().t_s) return Vec3::Zero();
  for (std::size_t k = 1; k < knots_.size(); ++k)
    if (t <= knots_[k].t_s) {
      const double f = (t - knots_[k - 1].t_s) / (knots_[k].t_s - knots_[k - 1].t_s);
      return (1.0 - f) * knots_[k - 1].velocity_m_s + f * knots_[k].velocity_m_s;
    }
  return knots_.back().velocity_m_s;
}

Vec3 PiecewiseLinearVelocity::displacement_until(double t) const {
  Vec3 d = Vec3::Zero();
  for (std::size_t k = 1; k < knots_.size(); ++k) {
    const double a = knots_[k - 1].t_s, b = std::min(t, knots_[k].t_s);
    if (b <= a) break;
    // Trapezoid of the linear velocity on [a, b]: exact.
    d += 0.5 * (b - a) * (knots_[k - 1].velocity_m_s + velocity_at(b));
  }
  return d;
}

void PiecewiseLinearVelocity::advance(Wall& w, double t, double dt) {
  w.pose.origin_m += displacement_until(t + dt) - displacement_until(t);
  w.pose.velocity_m_s = velocity_at(t + dt);
}

double PiecewiseLinearVelocity::max_speed_m_s(double) const {
  double v = 0.0;
  for (const Knot& k : knots_) v = std::max(v, k.velocity_m_s.norm());
  return v;
}

}  // namespace seedcal
