#pragma once
// Normal elastic slot: Hertz's force between two elastic spheres (Hertz 1882; Johnson 1985,
// "Contact Mechanics", eq. 4.23; EDEM Theory Reference Guide, Hertz-Mindlin (no slip)). With d the
// overlap, R* the effective radius (1/R* = 1/R_i + 1/R_j; a wall has R = inf) and E* the effective
// modulus (1/E* = (1 - nu_i^2)/E_i + (1 - nu_j^2)/E_j, core/materials.hpp):
//
//   Sn  = dFn/dd = 2 E* sqrt(R* d)          normal contact stiffness
//   Fn  = 4/3 E* sqrt(R*) d^1.5 = 2/3 Sn d  elastic normal force, repulsive
//
// Sn also sets the normal dashpot (normal_damping.hpp), the tangential stiffness
// (tangential_spring.hpp) and the EPSD rolling stiffness (rolling_epsd.hpp).
#include "solver/contact/lanes.hpp"

namespace seedcal::lanes {

template <class T>
struct HertzNormal {
  T stiffness_n_m;  // Sn
  T force_n;        // the elastic part of Fn, >= 0
};

template <class O>
[[gnu::always_inline]] inline HertzNormal<typename O::T> hertz_normal(typename O::T e_star_pa,
                                                                     typename O::T r_star_m,
                                                                     typename O::T overlap_m) {
  using T = typename O::T;
  const T sn = 2.0 * e_star_pa * O::sqrt(r_star_m * overlap_m);
  return {sn, (2.0 / 3.0) * sn * overlap_m};
}

}  // namespace seedcal::lanes
