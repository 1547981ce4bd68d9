#pragma once
// Hertz-Mindlin (no slip) contact force, as in the common commercial formulation (EDEM Theory
// Reference Guide; Tsuji, Tanaka & Ishida 1992 for the damping; Mindlin 1949 for the tangential
// stiffness). With dn the overlap, R* the effective radius, m* the effective (body) mass:
//
//   Fn  = 4/3 E* sqrt(R*) dn^1.5                      elastic normal force
//   Sn  = 2 E* sqrt(R* dn)                            normal contact stiffness dFn/ddn
//   Fnd = -2 sqrt(5/6) beta sqrt(Sn m*) vn            normal damping (beta < 0: opposes vn)
//   St  = 8 G* sqrt(R* dn)                            tangential stiffness
//   Ft  = -St dt - 2 sqrt(5/6) beta sqrt(St m*) vt    spring on the accumulated tangential
//                                                     displacement dt, plus damping
//   |Ft| <= mu_s |Fn|                                 Coulomb limit; on slip the spring is reset
//                                                     so that it carries exactly the limit force
//
// `damping_scale` multiplies both damping coefficients: 1 for plain Hertz-Mindlin, 1/sqrt(n) for
// the multi-contact correction (see hmnr.hpp).
//
// Which velocity each term uses (velocity Verlet; the forces are evaluated at t_{n+1}, after the
// drift, when the bodies hold the half-step velocity v_{n+1/2}):
//   - the tangential spring grows by vt_{n+1/2} dt, the velocity the positions were drifted with,
//     so the spring stays consistent with the motion;
//   - the dashpots use the same half-step velocity by default, as LAMMPS and LIGGGHTS do
//     (ContactOptions::dashpot_predicted = false). With the half-step velocity a body whose
//     contacts damp it at the rate g (g = sum c_k / m for its translation, sum c_k r_k^2 / I for
//     its spin about the lever arms r_k) is kicked to (1 - g dt) of its velocity per step: stable
//     for g dt < 2.
//   - optionally, the predicted end-of-step velocity v~_{n+1} = v_{n+1/2} + dt/2 F_n / m (Groot &
//     Warren 1997, J. Chem. Phys. 107, 4423, eq. 17 with lambda = 1: an O(dt^2) estimate of
//     v_{n+1}). The half-step velocity lags half a step, which removes energy early in a contact:
//     at 10-20 steps per contact a binary impact set to e = 0.1 comes out 0.075-0.088 and one set
//     to 0.01 0.002-0.005, where the prediction gives 0.092-0.100 and 0.0096-0.0102
//     (docs/stability.md). But F_n holds the previous step's damping force, so the damping feeds
//     back on itself: with u the half-step velocity and b_n = dt F_n / m the recurrence is
//     u_{n+1} = u_n + b_n, b_n = -g dt (u_n + b_{n-1} / 2), whose root reaches -1 at g dt = 1,
//     half the half-step limit (lower still with the springs: docs/stability.md, "Dashpot
//     velocity"). A seed's spin in a packing at 200 kPa, with six to ten contacts each adding its
//     tangential damper at the lever r against I = 0.4 m r^2 for a sphere, reaches g dt = 1 at a
//     fifth of the Rayleigh step; the spins then flip sign every step and grow until the energy
//     guard stops the run (tests/physics/dashpot_stability_test.cpp).
//
// Tangential spring. It is kept in the current tangent plane with its length preserved (the
// contact frame rotates with the pair; Luding 2008, "Cohesive, frictional powders", sec. 2.2.3).
// On sliding the total tangential force is capped at the Coulomb limit and the spring reset so
// that the spring alone carries the limit force: the tangential damper then acts only while the
// contact sticks, and the force is continuous when sliding stops. LIGGGHTS and LAMMPS instead set
// the spring to carry the limit force plus the damping force, -(F_lim + c_t v_t) / S_t; early in
// an impact, where the damping term alone exceeds the limit, that stretches the spring backwards
// and the contact then under-shoots Coulomb friction (8 % too little tangential impulse for
// e = 0.45 in tests/physics/oblique_impact_test.cpp).
#include <cmath>

#include "solver/contact/contact_model.hpp"
#include "solver/contact/hertz_mindlin_lanes.hpp"
#include "solver/core/materials.hpp"
#include "solver/core/vec.hpp"

namespace seedcal {

// Geometry and kinematics of one sphere-level contact, seen from sphere i.
struct ContactKinematics {
  Vec3 normal;        // unit vector from i towards j (or towards the wall)
  double overlap_m;   // > 0
  double r_star_m;    // 1/R* = 1/R_i + 1/R_j (R_j = inf for a wall)
  double m_star_kg;   // 1/m* = 1/m_i + 1/m_j with body masses (m_j = inf for a wall)
  Vec3 v_rel_m_s;     // velocity of i's material point at the contact relative to j's, at the
                      // half step (spring increments)
  Vec3 v_rel_end_m_s; // the same from the predicted end-of-step velocities (dashpots)
};

struct ContactForce {
  Vec3 force_on_i_n;       // total (normal + tangential) force on i; j receives the opposite
  double normal_force_n;   // signed normal force (positive = repulsive), after any clipping
  double normal_stiffness_n_m;  // Sn, for the EPSD rolling spring
};

// One contact, in Eigen types; the formulas are those of contact/hertz_mindlin_lanes.hpp, which
// the sphere-sphere kernel runs on several contacts at once.
[[gnu::always_inline]] inline ContactForce hertz_mindlin(const PairConstants& c,
                                                        const ContactKinematics& k,
                                                        Vec3& tangential_disp_m, double dt_s,
                                                        double damping_scale, bool clip_attractive) {
  using V = lanes::V3<double>;
  const auto v3 = [](const Vec3& v) { return V{v.x(), v.y(), v.z()}; };
  const lanes::HmConstants<double> hc{c.e_star_pa, c.beta, c.static_friction,
                                      c.sqrt_tangential_ratio};
  V t = v3(tangential_disp_m);
  const lanes::HmResult<double> r = lanes::hertz_mindlin_lanes<lanes::ScalarOps>(
      hc, v3(k.normal), k.overlap_m, k.r_star_m, k.m_star_kg, v3(k.v_rel_m_s), v3(k.v_rel_end_m_s),
      t, dt_s, damping_scale, clip_attractive);
  tangential_disp_m = Vec3(t.x, t.y, t.z);
  return {Vec3(r.force_on_i_n.x, r.force_on_i_n.y, r.force_on_i_n.z), r.normal_force_n,
          r.normal_stiffness_n_m};
}

}  // namespace seedcal
