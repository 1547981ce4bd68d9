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
//   - the dashpots use the predicted end-of-step velocity v~_{n+1} = v_{n+1/2} + dt/2 F_n / m
//     (Groot & Warren 1997, J. Chem. Phys. 107, 4423, eq. 17 with lambda = 1: an O(dt^2) estimate
//     of v_{n+1}). With v_{n+1/2} instead the damping force lags half a step; that lag removes
//     energy early in the contact and lowered the restitution at 10-20 steps per contact from
//     0.1 to 0.075-0.088 and from 0.01 to 0.002-0.005 (docs/stability.md); with v~_{n+1} the same
//     runs give 0.092-0.100 and 0.0096-0.0102. The explicit dashpot stays stable for
//     c dt / m < 2 (Heun's method on dv/dt = -c v / m), far above what the stable time step allows.
#include <cmath>

#include "solver/contact/contact_model.hpp"
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

// sqrt(5/6), the Hertz-Mindlin damping prefactor.
inline constexpr double kSqrtFiveSixths = 0.91287092917527685576;

[[gnu::always_inline]] inline ContactForce hertz_mindlin(const PairConstants& c,
                                                        const ContactKinematics& k,
                                                        Vec3& tangential_disp_m, double dt_s,
                                                        double damping_scale, bool clip_attractive) {
  const double sqrt_rd = std::sqrt(k.r_star_m * k.overlap_m);
  const double sn = 2.0 * c.e_star_pa * sqrt_rd;
  const double st = sn * c.sqrt_tangential_ratio * c.sqrt_tangential_ratio;  // 8 G* sqrt(R* d)
  // -2 sqrt(5/6) beta >= 0 because beta <= 0.
  const double damp = -2.0 * kSqrtFiveSixths * c.beta * damping_scale;
  const double cn = damp * std::sqrt(sn * k.m_star_kg);
  const double ct = cn * c.sqrt_tangential_ratio;  // = damp sqrt(S_t m*)

  const Vec3 vt = k.v_rel_m_s - k.v_rel_m_s.dot(k.normal) * k.normal;  // spring increment
  const double vn_end = k.v_rel_end_m_s.dot(k.normal);                  // > 0: approaching
  const Vec3 vt_end = k.v_rel_end_m_s - vn_end * k.normal;               // dashpot

  // Fn_elastic = 4/3 E* sqrt(R*) dn^1.5 = 2/3 Sn dn.
  double fn = (2.0 / 3.0) * sn * k.overlap_m + cn * vn_end;
  if (clip_attractive && fn < 0.0) fn = 0.0;

  // Keep the tangential spring in the current tangent plane, preserving its length (the contact
  // frame rotates with the pair; Luding 2008, "Cohesive, frictional powders", sec. 2.2.3).
  const double len0_sq = tangential_disp_m.squaredNorm();
  const double along = tangential_disp_m.dot(k.normal);
  if (along != 0.0) {
    tangential_disp_m -= along * k.normal;
    const double len1_sq = len0_sq - along * along;
    if (len1_sq > 0.0) tangential_disp_m *= std::sqrt(len0_sq / len1_sq);
  }
  tangential_disp_m += vt * dt_s;

  // Tangential force on i opposes i's slip relative to j.
  Vec3 ft = -st * tangential_disp_m - ct * vt_end;
  const double ft_max = c.static_friction * std::abs(fn);
  const double ft_sq = ft.squaredNorm();
  if (ft_sq > ft_max * ft_max) {
    // Sliding: cap the total at the Coulomb limit and reset the spring so that the spring alone
    // carries the limit force; the tangential damper then acts only while the contact sticks, and
    // the force is continuous when sliding stops. LIGGGHTS and LAMMPS instead set the spring to carry the limit force plus the damping force,
    // -(F_lim + c_t v_t) / S_t; early in an impact, where the damping term alone exceeds the limit,
    // that stretches the spring backwards and the contact then under-shoots Coulomb friction (8 %
    // too little tangential impulse for e = 0.45 in tests/physics/oblique_impact_test.cpp).
    ft *= ft_max / std::sqrt(ft_sq);
    tangential_disp_m = st > 0.0 ? Vec3(ft * (-1.0 / st)) : Vec3::Zero();
  }
  return {-fn * k.normal + ft, fn, sn};
}

}  // namespace seedcal
