#pragma once
// Rolling slot, elastic-plastic spring-dashpot (EPSD), "type C" of Ai, Chen, Rotter & Ooi (2011),
// Powder Technol. 206, 269-282, eqs. 11-17:
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
// turned with the contact normal, its magnitude kept. Stable at rest: a resting particle has
// w_r = 0 and no torque.
#include "solver/contact/lanes.hpp"

namespace seedcal::lanes {

template <class T>
struct EpsdIn {
  V3<T> normal;             // contact normal (unit)
  V3<T> relative_spin;      // w_i - w_j at the half step, rad/s (spring increment)
  V3<T> relative_spin_end;  // w_i - w_j seen by the dashpots (contact_law.hpp says which)
  T rolling_friction;       // mu_r
  T normal_force_n;
  T normal_stiffness_n_m;   // k_n (the Hertz tangent stiffness Sn)
  T r_star_m;
  T rolling_inertia_kg_m2;  // I_r
};

// The rolling torque on i (j receives the opposite); updates the spring moment `m_k` (N m).
template <class O>
[[gnu::always_inline]] inline V3<typename O::T> epsd_torque(const EpsdIn<typename O::T>& in,
                                                            double damping_ratio, double dt_s,
                                                            V3<typename O::T>& m_k) {
  using T = typename O::T;
  const T zero = O::splat(0.0);
  const V3<T>& n = in.normal;
  const V3<T> wr = in.relative_spin - dot(in.relative_spin, n) * n;
  const T kr = 2.25 * in.normal_stiffness_n_m * in.rolling_friction * in.rolling_friction *
               in.r_star_m * in.r_star_m;
  // Into the current tangent plane, its magnitude kept.
  const T len0 = O::sqrt(dot(m_k, m_k));
  m_k = m_k - dot(m_k, n) * n;
  const T len1 = O::sqrt(dot(m_k, m_k));
  m_k = (len1 > zero ? len0 / len1 : O::splat(1.0)) * m_k;

  m_k = m_k - (kr * dt_s) * wr;
  const T m_max = in.rolling_friction * in.r_star_m * O::abs(in.normal_force_n);
  const T m = O::sqrt(dot(m_k, m_k));
  const auto mobilised = m >= m_max;
  // Fully mobilised: the spring held at the limit, no damping (type C, f = 0).
  const V3<T> at_limit = (m > zero ? m_max / m : O::splat(1.0)) * m_k;
  const T cr = damping_ratio * 2.0 * O::sqrt(in.rolling_inertia_kg_m2 * kr);
  const V3<T> wr_end = in.relative_spin_end - dot(in.relative_spin_end, n) * n;
  m_k = select(mobilised, at_limit, m_k);
  const V3<T> torque = select(mobilised, at_limit, m_k - cr * wr_end);
  // No rolling friction: no spring and no torque.
  const auto off = in.rolling_friction == zero;
  const V3<T> none{zero, zero, zero};
  m_k = select(off, none, m_k);
  return select(off, none, torque);
}

}  // namespace seedcal::lanes
