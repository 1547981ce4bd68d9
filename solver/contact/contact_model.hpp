#pragma once
// Which contact models a run uses; chosen once per run, the kernels are compiled per combination.
#include <string>
#include <string_view>

#include "solver/contact/model_kinds.hpp"

namespace seedcal {

struct ContactOptions {
  NormalModel normal = NormalModel::hertz_mindlin;
  RollingModel rolling = RollingModel::none;
  // Clip the normal force at zero (no attraction at the end of a damped contact). Off by default:
  // with the force unclipped the set restitution comes out exactly; clipping raises it (for
  // e = 0.45 to about 0.51, see tests/physics/restitution_test.cpp).
  bool clip_attractive = false;
  // CDT lever arm R_i. false: the contacting sphere's radius less half the overlap (the local
  // radius of curvature; for single spheres both choices are the same). true: the distance from
  // the contact point to the body's centre of mass, as EDEM's standard rolling friction defines
  // R_i ("the distance of the contact point from the center of mass", EDEM Creator physics guide,
  // Standard Rolling Friction Model): for a multi-sphere seed the outer spheres' contacts get a
  // longer lever than their own radius.
  bool cdt_lever_from_centre_of_mass = false;
  // CDT as static rolling friction (contact/rolling_cdt.hpp): the body's rolling torque, at most
  // sum mu_r |Fn| R_i, at most stops its rotation within the step and never reverses it. false:
  // the literal sign-function torque -mu_r |Fn| R_i w/|w|, whose direction flips every step on a
  // body at rest and shakes it by mu_r |Fn| R_i dt / I per step: harmless under gravity, of order
  // 10 rad/s per step for a 9 mm seed at 200 kPa (docs/contact_models.md). Config: [contact]
  // cdt_at_rest = "static" (true) or "literal" (false).
  bool cdt_stop_limit = true;
  // Which velocity the dashpots see (contact/contact_law.hpp, "Which velocity each term uses").
  // false (the default): the half-step velocity v_{n+1/2}, as LAMMPS and LIGGGHTS do; stable in
  // confined, many-contact packings up to about twice the damping rate of the other choice. true:
  // the predicted end-of-step velocity v_{n+1/2} + dt/2 F_n / m, which gives the set restitution of a
  // binary impact more closely at 10-20 steps per contact for e <= 0.1, but whose own damping
  // feeds back through F_n and goes unstable once a body's damping rate times dt reaches 1: the
  // spin of a seed with six or more contacts at 200 kPa does (docs/stability.md, "Dashpot
  // velocity"). Config: [contact] dashpot_velocity = "half_step" (false) or "predicted" (true).
  bool dashpot_predicted = false;
  // EPSD (type C) viscous damping ratio of the rolling dashpot, Ai et al. (2011) eq. 17; 0.3 is
  // their recommended value.
  double epsd_damping_ratio = 0.3;
};

const char* to_string(NormalModel m);
const char* to_string(RollingModel m);
bool parse_normal_model(std::string_view s, NormalModel& out);
bool parse_rolling_model(std::string_view s, RollingModel& out);

}  // namespace seedcal
