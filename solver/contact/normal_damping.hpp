#pragma once
// Normal damping slot: the viscous dashpot of Hertz-Mindlin (Tsuji, Tanaka & Ishida 1992, Powder
// Technol. 71, 239; EDEM Theory Reference Guide), with the multi-contact "new restitution" scale as
// its option. With Sn the normal stiffness (normal_elastic.hpp), m* the effective body mass
// (1/m* = 1/m_i + 1/m_j; a wall's is infinite) and e the coefficient of restitution:
//
//   beta = ln e / sqrt(ln^2 e + pi^2)                 (core/materials.hpp; beta <= 0)
//   cn   = -2 sqrt(5/6) beta s sqrt(Sn m*)            normal damping coefficient
//   Fnd  = cn vn                                      vn > 0 when approaching (it adds to Fn)
//
// The damping ratio of the contact is zeta = cn / (2 sqrt(Sn m*)) = -sqrt(5/6) beta s.
//
// s, the damping scale, is 1 for plain Hertz-Mindlin. HMNR, the multi-contact correction
// (Kruggel-Emden et al. 2008, Powder Technol. 184, 157; Hoehner et al. 2011, Powder Technol. 208,
// 643): when two rigid clumps (or a clump and a wall) touch at n sphere-level points at once, n
// spring-dashpots act in parallel between the same two bodies, i.e. one spring n k and one dashpot
// n c on the same mass m*, whose damping ratio is
//   zeta_n = n c / (2 sqrt(n k m*)) = sqrt(n) zeta.
// The energy lost per impact grows with it and the pair's restitution falls below the set value.
// s = 1/sqrt(n) restores zeta_n = zeta and therefore the set restitution; n is the number of
// sphere-level contacts between that body pair at the current step. The rule is exact for n equal,
// simultaneous contacts and an approximation otherwise (the papers above; tests/physics/
// hmnr_test.cpp drops a flat clump flat on a plate). The tangential dashpot takes the same scale
// (tangential_spring.hpp).
#include "solver/contact/lanes.hpp"

namespace seedcal {

// HMNR's damping scale s for a body pair touching at `contacts_of_pair` sphere-level points.
inline double hmnr_damping_scale(int contacts_of_pair) {
  return contacts_of_pair > 1 ? 1.0 / __builtin_sqrt(static_cast<double>(contacts_of_pair)) : 1.0;
}

namespace lanes {

// sqrt(5/6), the Hertz-Mindlin damping prefactor.
inline constexpr double kSqrtFiveSixths = 0.91287092917527685576;

// cn = -2 sqrt(5/6) beta s sqrt(Sn m*) (>= 0, since beta <= 0).
template <class O>
[[gnu::always_inline]] inline typename O::T normal_dashpot(typename O::T beta,
                                                          typename O::T damping_scale,
                                                          typename O::T stiffness_n_m,
                                                          typename O::T m_star_kg) {
  return -2.0 * kSqrtFiveSixths * beta * damping_scale * O::sqrt(stiffness_n_m * m_star_kg);
}

}  // namespace lanes
}  // namespace seedcal
