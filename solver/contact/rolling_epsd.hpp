#pragma once
// Elastic-plastic spring-dashpot (EPSD) rolling resistance, "type C" of Ai, Chen, Rotter & Ooi
// (2011), Powder Technol. 206, 269-282, eqs. 11-17:
//
//   k_r   = 2.25 k_n mu_r^2 R*^2                      rolling stiffness (eq. 13; Iwashita & Oda)
//   dM_k  = -k_r dtheta_r,  dtheta_r = w_r dt         incremental spring moment (eq. 11)
//   |M_k| <= M_m = mu_r R* |Fn|                       plastic limit (eq. 12)
//   M_d   = -C_r w_r,  C_r = eta_r 2 sqrt(I_r k_r)    viscous damping while not fully mobilised
//                                                     (eqs. 15-17; no damping at the limit, f = 0)
//   1/I_r = 1/(I_i + m_i r_i^2) + 1/(I_j + m_j r_j^2) equivalent rolling inertia about the contact
//
// w_r is the relative rolling angular velocity (w_i - w_j) projected on the tangent plane (the
// twisting component is not resisted). The spring moment is history: it is carried per contact and
// rotated with the contact normal. Stable at rest: a resting particle has w_r = 0 and no torque.
#include <cmath>

#include "solver/core/vec.hpp"

namespace seedcal {

struct EpsdInput {
  Vec3 normal;              // contact normal (unit)
  Vec3 relative_spin;       // w_i - w_j at the half step, rad/s (spring increment)
  Vec3 relative_spin_end;   // w_i - w_j from the predicted end-of-step spins (dashpot; see
                            // hertz_mindlin.hpp for why the two differ)
  double rolling_friction;  // mu_r
  double normal_force_n;
  double normal_stiffness_n_m;  // k_n (the Hertz tangent stiffness Sn)
  double r_star_m;
  double rolling_inertia;   // I_r, kg m2
  double damping_ratio;     // eta_r
  double dt_s;
};

// Returns the torque on i (j receives the opposite) and updates the spring moment history.
inline Vec3 epsd_torque(const EpsdInput& in, Vec3& spring_moment) {
  if (in.rolling_friction == 0.0) { spring_moment.setZero(); return Vec3::Zero(); }
  const Vec3 wr = in.relative_spin - in.relative_spin.dot(in.normal) * in.normal;
  const double kr = 2.25 * in.normal_stiffness_n_m * in.rolling_friction * in.rolling_friction *
                    in.r_star_m * in.r_star_m;
  // Rotate the stored moment into the current tangent plane, preserving its magnitude.
  const double len0 = spring_moment.norm();
  spring_moment -= spring_moment.dot(in.normal) * in.normal;
  const double len1 = spring_moment.norm();
  if (len1 > 0.0) spring_moment *= len0 / len1;

  spring_moment -= kr * in.dt_s * wr;
  const double m_max = in.rolling_friction * in.r_star_m * std::abs(in.normal_force_n);
  const double m = spring_moment.norm();
  if (m >= m_max) {
    if (m > 0.0) spring_moment *= m_max / m;
    return spring_moment;  // fully mobilised: no damping (type C, f = 0)
  }
  const double cr = in.damping_ratio * 2.0 * std::sqrt(in.rolling_inertia * kr);
  const Vec3 wr_end = in.relative_spin_end - in.relative_spin_end.dot(in.normal) * in.normal;
  return spring_moment - cr * wr_end;
}

}  // namespace seedcal
