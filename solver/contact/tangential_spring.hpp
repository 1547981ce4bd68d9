#pragma once
// Tangential slot: Mindlin's no-slip tangential spring with history, its dashpot, and Coulomb's
// limit (Mindlin 1949, J. Appl. Mech. 16, 259; Tsuji et al. 1992 for the damping; EDEM Theory
// Reference Guide, Hertz-Mindlin (no slip)). With Sn and cn the normal stiffness and dashpot
// (normal_elastic.hpp, normal_damping.hpp), G* the effective shear modulus (1/G* = (2 - nu_i)/G_i
// + (2 - nu_j)/G_j) and k^2 = St / Sn = 4 G* / E* (core/materials.hpp: sqrt_tangential_ratio):
//
//   St  = 8 G* sqrt(R* d) = k^2 Sn                  tangential stiffness
//   ct  = -2 sqrt(5/6) beta s sqrt(St m*) = k cn    tangential damping coefficient
//   Ft  = -St t - ct vt                             spring on the accumulated tangential
//                                                   displacement t, plus damping
//   |Ft| <= mu_s |Fn|                               Coulomb limit
//
// The spring t is the contact's history. At every step it is first turned into the current
// tangent plane with its length kept (the contact frame rotates with the pair; Luding 2008,
// "Cohesive, frictional powders", Granular Matter 10, 235, sec. 2.2.3), then grows by vt dt, the
// tangential part of the half-step relative velocity (the one the positions were drifted with).
//
// Sliding. When |Ft| exceeds the limit the total is scaled to it and the spring reset so that the
// spring alone carries the limit force, t = -Ft_lim / St: the damper then acts only while the
// contact sticks, and the force is continuous when sliding stops. LIGGGHTS and LAMMPS instead set
// the spring to carry the limit force plus the damping force, -(Ft_lim + ct vt) / St; early in an
// impact, where the damping term alone exceeds the limit, that stretches the spring backwards and
// the contact then under-shoots Coulomb friction (8 % too little tangential impulse for e = 0.45 in
// tests/physics/oblique_impact_test.cpp).
#include "solver/contact/lanes.hpp"

namespace seedcal::lanes {

template <class T>
struct TangentialIn {
  V3<T> normal;           // unit contact normal
  V3<T> v_rel_m_s;        // relative velocity of the contact points at the half step (spring)
  V3<T> v_rel_t_end_m_s;  // tangential part of the dashpots' relative velocity
  T normal_stiffness_n_m; // Sn
  T normal_dashpot;       // cn, with its damping scale
  T sqrt_tangential_ratio;  // k = sqrt(St / Sn)
  T static_friction;        // mu_s
  T normal_force_n;         // Fn, signed
};

// The tangential force on i; updates the spring `t` (m) in place.
template <class O>
[[gnu::always_inline]] inline V3<typename O::T> mindlin_tangential(
    const TangentialIn<typename O::T>& in, V3<typename O::T>& t, double dt_s) {
  using T = typename O::T;
  const T zero = O::splat(0.0);
  const V3<T>& n = in.normal;
  const T st = in.normal_stiffness_n_m * in.sqrt_tangential_ratio * in.sqrt_tangential_ratio;
  const T ct = in.normal_dashpot * in.sqrt_tangential_ratio;
  const V3<T> vt = in.v_rel_m_s - dot(in.v_rel_m_s, n) * n;

  // Into the current tangent plane with its length (Luding 2008, sec. 2.2.3), then the increment.
  const T len0_sq = dot(t, t);
  const T along = dot(t, n);
  t = t - along * n;
  const T len1_sq = len0_sq - along * along;
  const auto rescale = (along != zero) & (len1_sq > zero);
  const T factor = rescale ? O::sqrt(len0_sq / len1_sq) : O::splat(1.0);
  t = factor * t + O::splat(dt_s) * vt;

  // The force on i opposes i's slip relative to j.
  V3<T> ft = (-st) * t - ct * in.v_rel_t_end_m_s;
  const T ft_max = in.static_friction * O::abs(in.normal_force_n);
  const auto slide = dot(ft, ft) > ft_max * ft_max;
  if (O::any(slide)) {
    // Sliding: the total capped at the limit, the spring reset to carry exactly that force.
    const V3<T> ft_lim = (ft_max / O::sqrt(dot(ft, ft))) * ft;
    const T inv_st = st > zero ? -1.0 / st : zero;
    t = select(slide, inv_st * ft_lim, t);
    ft = select(slide, ft_lim, ft);
  }
  return ft;
}

}  // namespace seedcal::lanes
