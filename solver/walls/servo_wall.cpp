#include "solver/walls/servo_wall.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace seedcal {

Servo::Servo(const Vec3& direction, double target_force_n, double max_speed_m_s, double alpha)
    : dir_(direction.normalized()), target_(target_force_n), v_max_(max_speed_m_s), alpha_(alpha) {
  if (!(direction.norm() > 0.0)) throw std::invalid_argument("Servo: the direction must be non-zero");
  if (!(max_speed_m_s > 0.0)) throw std::invalid_argument("Servo: max_speed_m_s must be > 0");
  if (!(alpha > 0.0 && alpha < 1.0)) throw std::invalid_argument("Servo: alpha must be in (0, 1)");
}

std::shared_ptr<Servo> Servo::for_stress(const Vec3& direction, double stress_pa, double area_m2,
                                         double max_speed_m_s, double alpha) {
  if (!(area_m2 > 0.0)) throw std::invalid_argument("Servo::for_stress: area_m2 must be > 0");
  auto s = std::make_shared<Servo>(direction, stress_pa * area_m2, max_speed_m_s, alpha);
  s->area_ = area_m2;
  return s;
}

void Servo::advance(Wall& w, double, double dt) {
  // v = alpha (F_t - F) / (k_w dt), capped at v_max (header); no contact: approach at the cap.
  const double error = target_ - measured_force_n(w);
  double v = w.contact_stiffness_n_m > 0.0 ? alpha_ * error / (w.contact_stiffness_n_m * dt) : v_max_;
  v = std::clamp(v, -v_max_, v_max_);
  if (seat_) {
    // Resting on the seat: it may lift (v < 0) but not move further along the direction.
    const double gap = (*seat_ - w.pose.origin_m).dot(dir_);  // >= 0 while clear of the seat
    v = std::min(v, gap / dt);
  }
  w.pose.velocity_m_s = v * dir_ + transverse_;
  w.pose.origin_m += dt * w.pose.velocity_m_s;
}

}  // namespace seedcal
