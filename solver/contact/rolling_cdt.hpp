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
// (it is not an action-reaction pair).
//
// Static rolling friction (ContactOptions::cdt_stop_limit, the default). Taken literally, w/|w|
// has no limit at rest: the torque flips every step and shakes a resting body by
// mu_r |Fn| R dt / I per step. Under gravity that is negligible, but for a 9 mm seed at 200 kPa
// (|Fn| ~ 16 N per contact, several contacts) it is of order 10 rad/s per step, far above the 0.01 m/s of a
// direct shear: the shaken packing lost a third of its strength and its strength depended on the
// shear speed (docs/contact_models.md). As Coulomb friction holds a contact below mu |Fn|, the
// rolling torque is therefore the one that stops the body's rotation, bounded by the capacity
// C = sum_i mu_r |Fn_i| R_i over the body's contacts: with L_p = L + h T the angular momentum the
// body would reach over the span h the torque acts on (dt in velocity Verlet) under its other
// torques T,
//   tau = -min(C, |L_p| / h) L_p / |L_p|.
// A body whose rotation C cannot stop within h gets the full -C along its spin (the literal CDT;
// the same as -C w/|w| for a sphere); a body that C can stop is stopped and stays at rest (tested in
// tests/physics/rolling_test.cpp). The literal form stays available: `[contact] cdt_at_rest = "literal"`.
#include <algorithm>
#include <cmath>

#include "solver/core/vec.hpp"

namespace seedcal {

// Static rolling friction: the torque per unit of capacity (multiply by C) that at most stops the
// body's angular momentum L (kg m2/s) within h under its other torques T (N m).
inline Vec3 cdt_stop_limited(const Vec3& angular_momentum, const Vec3& other_torque_n_m, double capacity_n_m,
                             double h_s) {
  const Vec3 lp = angular_momentum + h_s * other_torque_n_m;
  const double n = lp.norm();
  if (n == 0.0 || capacity_n_m <= 0.0) return Vec3::Zero();
  return (-std::min(capacity_n_m, n / h_s) / (capacity_n_m * n)) * lp;
}

// The literal CDT direction -w/|w| (zero below 1e-12 rad/s, where the direction is undefined).
inline Vec3 cdt_sign_direction(const Vec3& angular_velocity) {
  const double w = angular_velocity.norm();
  return w > 1e-12 ? Vec3(angular_velocity * (-1.0 / w)) : Vec3::Zero();
}

}  // namespace seedcal
