#pragma once
// Rolling slot, constant directional torque (CDT), as in the commercial code the paper used (EDEM
// Theory Reference Guide, "rolling friction"; Zhou et al. 1999, Powder Technol. 102, 59):
//
//   tau_i = -mu_r |Fn| R_i w_i / |w_i|
//
// with w_i the angular velocity of body i itself (not the relative spin) and R_i the distance from
// the contact point to the centre of the contacting sphere, or, with
// ContactOptions::cdt_lever_from_centre_of_mass, to the body's centre of mass (EDEM's definition:
// "the distance of the contact point from the center of mass"; the same for a single sphere, longer
// for a clump's outer spheres). It is applied to each body separately (it is not an
// action-reaction pair).
//
// All of a body's contacts share its spin direction, so the contacts' torques add up to
// -C w/|w| with the capacity C = sum_i mu_r |Fn_i| R_i. Each contact therefore only adds its share
// mu_r |Fn| R_i to its body's C (here); the body's torque is applied once per step from C
// (rolling_cdt_torque.hpp, which also makes it static rolling friction at rest).
#include "solver/contact/lanes.hpp"

namespace seedcal::lanes {

// One contact's share of its body's capacity is mu_r |Fn| R with R the body's lever: this is
// mu_r |Fn|, the share per metre of lever (contact_law.hpp multiplies by each body's R).
template <class O>
[[gnu::always_inline]] inline typename O::T cdt_capacity_per_lever(typename O::T rolling_friction,
                                                                   typename O::T normal_force_n) {
  return rolling_friction * O::abs(normal_force_n);
}

}  // namespace seedcal::lanes
