#pragma once
// Hertz-Mindlin (no slip) written once for any lane type: `double` (one contact) or a GCC vector
// of doubles (several contacts at once, sim/pair_batch_avx2.cpp and sim/pair_batch_avx512.cpp).
// The formulas, their sources and the choice of velocities are documented in
// contact/hertz_mindlin.hpp, whose scalar hertz_mindlin() calls this code; the sphere-sphere and
// sphere-wall kernels call it with four or eight lanes.
//
// Lane types. `O` supplies the lane type O::T and sqrt, abs, splat and any-of-mask; the arithmetic,
// comparisons and `mask ? a : b` are the language's own (GCC and Clang give vector types the same
// operators as double). Every lane is computed with the same operations in the same order, and no
// operation is fused (the lane translation units are built without FMA contraction), so one
// contact gives the same bits on one lane as on four or eight.
//
// No Eigen here: the vector translation units are compiled for AVX2 and AVX-512F and must not
// emit copies of library inline functions that a baseline translation unit might link to.

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

// sqrt(5/6), the Hertz-Mindlin damping prefactor.
inline constexpr double kSqrtFiveSixths = 0.91287092917527685576;

template <class T>
struct HmConstants {
  T e_star_pa, beta, static_friction, sqrt_tangential_ratio;
};

template <class T>
struct HmResult {
  V3<T> force_on_i_n;      // total (normal + tangential) force on i
  T normal_force_n;        // signed, positive = repulsive, after any clipping
  T normal_stiffness_n_m;  // Sn
};

// Hertz-Mindlin force of one contact per lane; updates the tangential spring `t` (m) in place.
// n: unit normal from i to j; vrel / vrel_end: relative velocity of i's contact point to j's at
// the half step (spring increment) and predicted at the step's end (dashpots).
template <class O>
[[gnu::always_inline]] inline HmResult<typename O::T> hertz_mindlin_lanes(
    const HmConstants<typename O::T>& c, const V3<typename O::T>& n, typename O::T overlap,
    typename O::T r_star, typename O::T m_star, const V3<typename O::T>& vrel,
    const V3<typename O::T>& vrel_end, V3<typename O::T>& t, double dt_s,
    typename O::T damping_scale, bool clip_attractive) {
  using T = typename O::T;
  const T zero = O::splat(0.0);
  const T one = O::splat(1.0);
  const T sqrt_rd = O::sqrt(r_star * overlap);
  const T sn = 2.0 * c.e_star_pa * sqrt_rd;
  const T st = sn * c.sqrt_tangential_ratio * c.sqrt_tangential_ratio;  // 8 G* sqrt(R* d)
  // -2 sqrt(5/6) beta >= 0 because beta <= 0.
  const T damp = -2.0 * kSqrtFiveSixths * c.beta * damping_scale;
  const T cn = damp * O::sqrt(sn * m_star);
  const T ct = cn * c.sqrt_tangential_ratio;

  const V3<T> vt = vrel - dot(vrel, n) * n;  // spring increment
  const T vn_end = dot(vrel_end, n);          // > 0: approaching
  const V3<T> vt_end = vrel_end - vn_end * n;  // dashpot

  // Fn_elastic = 4/3 E* sqrt(R*) dn^1.5 = 2/3 Sn dn.
  T fn = (2.0 / 3.0) * sn * overlap + cn * vn_end;
  if (clip_attractive) fn = fn < zero ? zero : fn;

  // Keep the spring in the current tangent plane with its length (Luding 2008, sec. 2.2.3).
  const T len0_sq = dot(t, t);
  const T along = dot(t, n);
  t = t - along * n;
  const T len1_sq = len0_sq - along * along;
  const auto rescale = (along != zero) & (len1_sq > zero);
  const T factor = rescale ? O::sqrt(len0_sq / len1_sq) : one;
  t = factor * t + O::splat(dt_s) * vt;

  // Tangential force on i opposes i's slip relative to j.
  V3<T> ft = (-st) * t - ct * vt_end;
  const T ft_max = c.static_friction * O::abs(fn);
  const auto slide = dot(ft, ft) > ft_max * ft_max;
  if (O::any(slide)) {
    // Sliding: the total is capped at the Coulomb limit and the spring reset to carry exactly
    // that force (hertz_mindlin.hpp explains why not LIGGGHTS's limit-plus-damping reset).
    const V3<T> ft_lim = (ft_max / O::sqrt(dot(ft, ft))) * ft;
    const T inv_st = st > zero ? -1.0 / st : zero;
    t = select(slide, inv_st * ft_lim, t);
    ft = select(slide, ft_lim, ft);
  }
  return {(-fn) * n + ft, fn, sn};
}

}  // namespace seedcal::lanes
