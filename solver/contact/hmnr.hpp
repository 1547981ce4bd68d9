#pragma once
// The multi-contact "new restitution" correction (HMNR).
//
// Problem (Kruggel-Emden et al. 2008, Powder Technol. 184, 157; Hoehner et al. 2011, Powder
// Technol. 208, 643): when two rigid clumps (or a clump and a wall) touch at n sphere-level points
// at once, plain Hertz-Mindlin puts n spring-dashpots in parallel between the same two bodies.
//
// Derivation of the correction used here. Each sphere contact has a stiffness k and a damping
// coefficient c = -2 sqrt(5/6) beta sqrt(k m*), i.e. a damping ratio zeta = c / (2 sqrt(k m*)) set
// by the restitution through beta. For n equal contacts acting together on the same two bodies,
// the pair behaves as one spring nk and one dashpot nc on the same mass m*:
//   zeta_n = n c / (2 sqrt(n k m*)) = sqrt(n) zeta.
// The damping ratio, and with it the energy lost per impact, grows like sqrt(n), so the pair's
// restitution falls below the set value. Dividing each contact's damping by sqrt(n) restores
// zeta_n = zeta and therefore the set restitution. n is the number of sphere-level contacts between
// that body pair at the current step. The rule is exact for n equal, simultaneous contacts; for
// unequal or staggered contacts it is an approximation (see the papers above), tested in
// tests/physics/hmnr_test.cpp with a flat clump dropped flat on a plate.
#include <cmath>

namespace seedcal {

inline double hmnr_damping_scale(int contacts_of_pair) {
  return contacts_of_pair > 1 ? 1.0 / std::sqrt(static_cast<double>(contacts_of_pair)) : 1.0;
}

}  // namespace seedcal
