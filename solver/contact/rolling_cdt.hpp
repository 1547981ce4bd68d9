#pragma once
// Constant directional torque (CDT) rolling resistance, as in the commercial code the paper used
// (EDEM Theory Reference Guide, "rolling friction"; Zhou et al. 1999, Powder Technol. 102, 59):
//
//   tau_i = -mu_r |Fn| R_i w_i / |w_i|
//
// with w_i the angular velocity of body i itself (not the relative spin) and R_i the distance from
// the contact point to the centre of the contacting sphere, or, with
// ContactOptions::cdt_lever_from_centre_of_mass, to the body's centre of mass (EDEM's definition:
// "the distance of the contact point from the center of mass"; the same for a single sphere, longer
// for a clump's outer spheres). It is applied to each body separately
// (it is not an action-reaction pair). Known weakness: at rest w/|w| has no limit, so a resting
// particle keeps a small spin jitter of order mu_r |Fn| R dt / I; the EPSD model does not
// (measured in tests/physics/rolling_test.cpp).
#include <cmath>

#include "solver/core/vec.hpp"

namespace seedcal {

inline Vec3 cdt_torque(double rolling_friction, double normal_force_n, double lever_m,
                       const Vec3& body_angular_velocity) {
  const double w = body_angular_velocity.norm();
  // Below this spin the direction is undefined; 1e-12 rad/s is far below any physical rotation.
  if (w < 1e-12 || rolling_friction == 0.0) return Vec3::Zero();
  return (-rolling_friction * std::abs(normal_force_n) * lever_m / w) * body_angular_velocity;
}

// The same with the body's spin direction w/|w| precomputed once per step (zero when |w| is
// below 1e-12 rad/s), so each contact needs no square root.
[[gnu::always_inline]] inline Vec3 cdt_torque_dir(double rolling_friction, double normal_force_n,
                                                 double lever_m, const Vec3& spin_direction) {
  return (-rolling_friction * std::abs(normal_force_n) * lever_m) * spin_direction;
}

}  // namespace seedcal
