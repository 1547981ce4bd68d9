#pragma once
// The CDT rolling torque of a body (rolling_cdt.hpp has the model and each contact's share of the
// capacity): applied once per body and step by the force reduction (sim/forces.cpp), after every
// contact has added its capacity mu_r |Fn| R_i to the body's total C.
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
// tests/physics/rolling_test.cpp and contact/rolling_cdt_test.cpp). The literal form stays
// available: `[contact] cdt_at_rest = "literal"`.
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
  // min(C, |L_p| / h) / (C |L_p|) = 1 / max(|L_p|, h C): one division a body instead of two.
  return (-1.0 / std::max(n, h_s * capacity_n_m)) * lp;
}

// The literal CDT direction -w/|w| (zero below 1e-12 rad/s, where the direction is undefined).
inline Vec3 cdt_sign_direction(const Vec3& angular_velocity) {
  const double w = angular_velocity.norm();
  return w > 1e-12 ? Vec3(angular_velocity * (-1.0 / w)) : Vec3::Zero();
}

}  // namespace seedcal
