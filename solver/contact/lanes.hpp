#pragma once
// Lane types for the contact law (contact/contact_law.hpp): the slots are written once for any
// lane type `O`, which supplies the lane type O::T and sqrt, abs, splat, gather and any-of-mask;
// the arithmetic, comparisons and `mask ? a : b` are the language's own (GCC and Clang give vector
// types the same operators as double). `ScalarOps` is one contact on a plain double; the vector
// lane types are in sim/pair_batch_avx2.cpp (four lanes) and sim/pair_batch_avx512.cpp (eight).
// Every lane is computed with the same operations in the same order, and no operation is fused
// (the vector translation units are built without FMA contraction), so one contact gives the same
// bits on one lane as on four or eight.
//
// No Eigen and no library headers here, nor in the slot headers: the vector translation units are
// compiled for AVX2 and AVX-512F and must not emit copies of library inline functions that a
// baseline translation unit might link to.

namespace seedcal::lanes {

template <class T>
struct V3 {
  T x, y, z;
};

template <class T>
[[gnu::always_inline]] inline V3<T> operator+(const V3<T>& a, const V3<T>& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <class T>
[[gnu::always_inline]] inline V3<T> operator-(const V3<T>& a, const V3<T>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class T>
[[gnu::always_inline]] inline V3<T> operator*(const T& s, const V3<T>& a) {
  return {s * a.x, s * a.y, s * a.z};
}
template <class T>
[[gnu::always_inline]] inline T dot(const V3<T>& a, const V3<T>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class T>
[[gnu::always_inline]] inline V3<T> cross(const V3<T>& a, const V3<T>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class T, class M>
[[gnu::always_inline]] inline V3<T> select(const M& m, const V3<T>& a, const V3<T>& b) {
  return {m ? a.x : b.x, m ? a.y : b.y, m ? a.z : b.z};
}

// One lane: plain double.
struct ScalarOps {
  using T = double;
  static constexpr int lanes = 1;
  [[gnu::always_inline]] static double sqrt(double x) { return __builtin_sqrt(x); }
  [[gnu::always_inline]] static double abs(double x) { return __builtin_fabs(x); }
  [[gnu::always_inline]] static bool any(bool m) { return m; }
  [[gnu::always_inline]] static double splat(double x) { return x; }
  // Lane l of field `offset` comes from record p[l].
  [[gnu::always_inline]] static double gather(const double* const* p, int offset) {
    return p[0][offset];
  }
  [[gnu::always_inline]] static void store(double* out, double x) { out[0] = x; }
  // Fields offset .. offset+3 of each lane's record.
  [[gnu::always_inline]] static void load4(const double* const* p, int offset, double& a, double& b,
                                           double& c, double& d) {
    a = p[0][offset];
    b = p[0][offset + 1];
    c = p[0][offset + 2];
    d = p[0][offset + 3];
  }
  // out[lane][0..7] = the eight values of that lane.
  [[gnu::always_inline]] static void store_lanes8(double (*out)[8], double a0, double a1, double a2,
                                                  double a3, double a4, double a5, double a6,
                                                  double a7) {
    const double v[8] = {a0, a1, a2, a3, a4, a5, a6, a7};
    for (int i = 0; i < 8; ++i) out[0][i] = v[i];
  }
  [[gnu::always_inline]] static void add8(double* acc, const double* v) {
    for (int i = 0; i < 8; ++i) acc[i] += v[i];
  }
  [[gnu::always_inline]] static void sub8(double* acc, const double* v) {
    for (int i = 0; i < 8; ++i) acc[i] -= v[i];
  }
};

}  // namespace seedcal::lanes
