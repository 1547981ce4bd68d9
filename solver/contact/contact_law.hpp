#pragma once
// The contact law, composed of its slots (the slot design of LAMMPS's granular pair style): the
// normal elastic force (normal_elastic.hpp), the normal damping with HMNR's scale as its option
// (normal_damping.hpp), the tangential spring with history and Coulomb's limit
// (tangential_spring.hpp), and the rolling resistance, none, CDT (rolling_cdt.hpp) or EPSD
// (rolling_epsd.hpp). Each slot holds its formula and source, with a test on one contact beside
// it. Together the first three are Hertz-Mindlin (no slip), as in the common commercial
// formulation (EDEM Theory Reference Guide):
//
//   Fn = 4/3 E* sqrt(R*) d^1.5 + cn vn,   Ft = -St t - ct vt,   |Ft| <= mu_s |Fn|
//
// contact_law() below is the one body every contact runs: the sphere-sphere and the sphere-wall
// kernels (sim/pair_batch_lanes.hpp) gather their pairs' geometry into lanes, call it, and add the
// results to the bodies, at one, four or eight lanes.
//
// Which velocity each term uses (velocity Verlet; the forces are evaluated at t_{n+1}, after the
// drift, when the bodies hold the half-step velocity v_{n+1/2}):
//   - the tangential spring grows by vt_{n+1/2} dt, the velocity the positions were drifted with,
//     so the spring stays consistent with the motion (and so does EPSD's rolling spring);
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
//     (docs/results/stability.md). But F_n holds the previous step's damping force, so the damping
//     feeds back on itself: with u the half-step velocity and b_n = dt F_n / m the recurrence is
//     u_{n+1} = u_n + b_n, b_n = -g dt (u_n + b_{n-1} / 2), whose root reaches -1 at g dt = 1,
//     half the half-step limit (lower still with the springs: docs/stability.md, "Dashpot
//     velocity"). A seed's spin in a packing at 200 kPa, with six to ten contacts each adding its
//     tangential damper at the lever r against I = 0.4 m r^2 for a sphere, reaches g dt = 1 at a
//     fifth of the Rayleigh step; the spins then flip sign every step and grow until the energy
//     guard stops the run (tests/physics/dashpot_stability_test.cpp).
// The kernels hand both velocities to the law; the Simulation makes the "end" ones equal to the
// half-step ones unless the predicted velocity is chosen (integrate/velocity_verlet.hpp, VerletPass),
// and then the kernels hand the half-step one twice instead of loading and combining the end ones
// (PairBatchArgs::end_velocities).
#include "solver/contact/lanes.hpp"
#include "solver/contact/model_kinds.hpp"
#include "solver/contact/normal_damping.hpp"
#include "solver/contact/normal_elastic.hpp"
#include "solver/contact/rolling_cdt.hpp"
#include "solver/contact/rolling_epsd.hpp"
#include "solver/contact/tangential_spring.hpp"

namespace seedcal::lanes {

// The constants of one material pair (core/materials.hpp: PairConstants).
template <class T>
struct ContactLaw {
  T e_star_pa, beta, static_friction, rolling_friction, sqrt_tangential_ratio;
};

// One contact seen from i: geometry and kinematics.
template <class T>
struct ContactKinematics {
  V3<T> normal;         // unit, from i towards j (or towards the wall)
  T overlap_m;          // > 0
  T r_star_m;           // 1/R* = 1/R_i + 1/R_j (R_j = inf for a wall)
  T m_star_kg;          // 1/m* = 1/m_i + 1/m_j with body masses (m_j = inf for a wall)
  V3<T> v_rel_m_s;      // velocity of i's material point at the contact relative to j's, at the
                        // half step (spring increments)
  V3<T> v_rel_end_m_s;  // the same as the dashpots see it
  T damping_scale;      // 1, or HMNR's 1/sqrt(n) (normal_damping.hpp)
};

// What the law needs of the bodies' rotation: the lever arm from each body's centre of mass to
// the contact point (`Bodies` = 2 for two spheres, 1 against a wall: the j fields are then not
// read), CDT's lever R of each, and for EPSD the relative spins and the rolling inertia. Named
// fields, not arrays: the vector kernels keep every field in registers.
template <class T, int Bodies>
struct ContactRotation {
  V3<T> arm_i_m, arm_j_m;
  T cdt_lever_i_m, cdt_lever_j_m;
  V3<T> relative_spin, relative_spin_end;  // EPSD: w_i - w_j (a wall's spin for j)
  T rolling_inertia_kg_m2;                 // EPSD: I_r
};

template <class T, int Bodies>
struct ContactResult {
  V3<T> force_on_i_n;              // normal + tangential; j receives the opposite
  V3<T> torque_i_n_m;              // arm_i x force_on_i, on i
  V3<T> torque_j_n_m;              // arm_j x force_on_i: j receives its opposite (Bodies = 2)
  T roll_capacity_i_n_m;           // CDT: each body's share of its capacity (0 otherwise)
  T roll_capacity_j_n_m;           // (Bodies = 2)
  V3<T> rolling_torque_n_m;        // EPSD: on i, j receives the opposite (0 otherwise)
  T normal_force_n;                // signed, positive = repulsive, after any clipping
  T normal_stiffness_n_m;          // Sn
};

struct ContactSettings {
  double dt_s = 0.0;
  bool clip_attractive = false;     // ContactOptions::clip_attractive
  double epsd_damping_ratio = 0.0;  // ContactOptions::epsd_damping_ratio
};

template <class T>
struct HertzMindlinForce {
  V3<T> force_on_i_n;
  T normal_force_n;
  T normal_stiffness_n_m;
};

// Hertz-Mindlin of one contact per lane: the normal force (elastic plus damping) and the
// tangential force; updates the tangential spring `t` (m) in place.
template <class O>
[[gnu::always_inline]] inline HertzMindlinForce<typename O::T> hertz_mindlin(
    const ContactLaw<typename O::T>& c, const ContactKinematics<typename O::T>& k,
    V3<typename O::T>& t, const ContactSettings& s) {
  using T = typename O::T;
  const HertzNormal<T> elastic = hertz_normal<O>(c.e_star_pa, k.r_star_m, k.overlap_m);
  const T cn = normal_dashpot<O>(c.beta, k.damping_scale, elastic.stiffness_n_m, k.m_star_kg);
  const V3<T>& n = k.normal;
  const T vn_end = dot(k.v_rel_end_m_s, n);  // > 0: approaching
  T fn = elastic.force_n + cn * vn_end;
  if (s.clip_attractive) fn = fn < O::splat(0.0) ? O::splat(0.0) : fn;
  const TangentialIn<T> tin{n, k.v_rel_m_s, k.v_rel_end_m_s - vn_end * n, elastic.stiffness_n_m,
                            cn, c.sqrt_tangential_ratio, c.static_friction, fn};
  const V3<T> ft = mindlin_tangential<O>(tin, t, s.dt_s);
  return {(-fn) * n + ft, fn, elastic.stiffness_n_m};
}

// The whole law of one contact per lane: Hertz-Mindlin, the force's torque about each body's
// centre of mass, and the rolling resistance RM. `t` is the tangential spring (m), `m_k` EPSD's
// rolling spring (N m; untouched otherwise).
template <class O, RollingModel RM, int Bodies>
[[gnu::always_inline]] inline ContactResult<typename O::T, Bodies> contact_law(
    const ContactLaw<typename O::T>& c, const ContactKinematics<typename O::T>& k,
    const ContactRotation<typename O::T, Bodies>& rot, V3<typename O::T>& t,
    V3<typename O::T>& m_k, const ContactSettings& s) {
  using T = typename O::T;
  const T zero = O::splat(0.0);
  const HertzMindlinForce<T> f = hertz_mindlin<O>(c, k, t, s);
  ContactResult<T, Bodies> r;
  r.force_on_i_n = f.force_on_i_n;
  r.normal_force_n = f.normal_force_n;
  r.normal_stiffness_n_m = f.normal_stiffness_n_m;
  r.torque_i_n_m = cross(rot.arm_i_m, f.force_on_i_n);
  if constexpr (Bodies == 2) r.torque_j_n_m = cross(rot.arm_j_m, f.force_on_i_n);
  r.roll_capacity_i_n_m = r.roll_capacity_j_n_m = zero;
  r.rolling_torque_n_m = {zero, zero, zero};
  if constexpr (RM == RollingModel::cdt) {
    const T per_lever = cdt_capacity_per_lever<O>(c.rolling_friction, f.normal_force_n);
    r.roll_capacity_i_n_m = per_lever * rot.cdt_lever_i_m;
    if constexpr (Bodies == 2) r.roll_capacity_j_n_m = per_lever * rot.cdt_lever_j_m;
  } else if constexpr (RM == RollingModel::epsd) {
    const EpsdIn<T> in{k.normal,           rot.relative_spin, rot.relative_spin_end,
                       c.rolling_friction, f.normal_force_n,  f.normal_stiffness_n_m,
                       k.r_star_m,         rot.rolling_inertia_kg_m2};
    r.rolling_torque_n_m = epsd_torque<O>(in, s.epsd_damping_ratio, s.dt_s, m_k);
  }
  return r;
}

}  // namespace seedcal::lanes
