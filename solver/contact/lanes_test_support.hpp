#pragma once
// For the slot tests: a four-lane type built on GCC's generic vectors (no instruction-set
// intrinsics, so it runs on any machine), and helpers that run a slot on four lanes and check each
// lane against the same slot on one lane, bit for bit (contact/lanes.hpp: every lane runs the same
// operations in the same order). The tests that include it are built with -Wno-psabi: GCC notes
// that 32-byte vectors pass differently in a baseline and an AVX build, and here they never cross
// a translation unit.
#include <gtest/gtest.h>

#include <cstring>

#include "solver/contact/lanes.hpp"

namespace seedcal::lanes::testing {

typedef double G4 __attribute__((vector_size(32)));

struct Generic4Ops {
  using T = G4;
  static constexpr int lanes = 4;
  static T sqrt(T x) {
    for (int l = 0; l < 4; ++l) x[l] = __builtin_sqrt(x[l]);
    return x;
  }
  static T abs(T x) {
    for (int l = 0; l < 4; ++l) x[l] = __builtin_fabs(x[l]);
    return x;
  }
  template <class M>
  static bool any(M m) {
    for (int l = 0; l < 4; ++l)
      if (m[l]) return true;
    return false;
  }
  static T splat(double x) { return T{x, x, x, x}; }
};

inline G4 lanes4(double a, double b, double c, double d) { return G4{a, b, c, d}; }
inline V3<G4> lanes4(const V3<double>& a, const V3<double>& b, const V3<double>& c,
                     const V3<double>& d) {
  return {G4{a.x, b.x, c.x, d.x}, G4{a.y, b.y, c.y, d.y}, G4{a.z, b.z, c.z, d.z}};
}
inline V3<double> lane(const V3<G4>& v, int l) { return {v.x[l], v.y[l], v.z[l]}; }

inline bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
inline bool same_bits(const V3<double>& a, const V3<double>& b) {
  return same_bits(a.x, b.x) && same_bits(a.y, b.y) && same_bits(a.z, b.z);
}
inline double norm(const V3<double>& v) { return __builtin_sqrt(dot(v, v)); }

}  // namespace seedcal::lanes::testing
