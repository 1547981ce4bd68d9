// The eight-lane batch kernel (sim/pair_batch.hpp). Built with -mavx512f and without FMA
// contraction (solver/CMakeLists.txt); called only where pair_batch_avx512_usable(). Everything but
// the entry points has internal linkage, so no AVX-512 code can stand in for a baseline function
// at link time. The lanes run the same operations as the one- and four-lane kernels (IEEE
// division and square root are correctly rounded at any width), so all three give the same bits.
#include "solver/sim/pair_batch_lanes.hpp"

#ifdef __AVX512F__
#include "solver/sim/pair_batch_transpose.hpp"

namespace seedcal {
namespace {

// Eight doubles; __m512d itself carries may_alias, which a template argument would drop.
typedef double V8d __attribute__((vector_size(64)));

// The halves of eight lanes. Written as shuffles: GCC 12's _mm512_insertf64x4 and
// _mm512_sqrt_pd start from _mm512_undefined_pd(), which -Wmaybe-uninitialized reports.
typedef double V4d __attribute__((vector_size(32)));
[[gnu::always_inline]] inline V8d join(V4d lo, V4d hi) {
  return __builtin_shufflevector(lo, hi, 0, 1, 2, 3, 4, 5, 6, 7);
}
[[gnu::always_inline]] inline V4d low_half(V8d v) { return __builtin_shufflevector(v, v, 0, 1, 2, 3); }
[[gnu::always_inline]] inline V4d high_half(V8d v) { return __builtin_shufflevector(v, v, 4, 5, 6, 7); }

struct Avx512Ops {
  using T = V8d;
  static constexpr int lanes = 8;
  [[gnu::always_inline]] static T sqrt(T x) { return _mm512_mask_sqrt_pd(x, 0xFF, x); }
  [[gnu::always_inline]] static T abs(T x) { return _mm512_abs_pd(x); }
  template <class M>
  [[gnu::always_inline]] static bool any(M m) {
    const __m512i v = reinterpret_cast<__m512i>(m);
    return _mm512_test_epi64_mask(v, v) != 0;
  }
  [[gnu::always_inline]] static T splat(double x) { return _mm512_set1_pd(x); }
  [[gnu::always_inline]] static T gather(const double* const* p, int offset) {
    return _mm512_set_pd(p[7][offset], p[6][offset], p[5][offset], p[4][offset], p[3][offset],
                         p[2][offset], p[1][offset], p[0][offset]);
  }
  [[gnu::always_inline]] static void store(double* out, T x) { _mm512_store_pd(out, x); }
  // Fields offset .. offset+3 of each lane's record, one vector per field: two 4x4 transposes,
  // lanes 0-3 in the low halves and 4-7 in the high ones.
  [[gnu::always_inline]] static void load4(const double* const* p, int offset, T& a, T& b, T& c,
                                           T& d) {
    __m256d a0 = _mm256_loadu_pd(p[0] + offset), b0 = _mm256_loadu_pd(p[1] + offset);
    __m256d c0 = _mm256_loadu_pd(p[2] + offset), d0 = _mm256_loadu_pd(p[3] + offset);
    __m256d a1 = _mm256_loadu_pd(p[4] + offset), b1 = _mm256_loadu_pd(p[5] + offset);
    __m256d c1 = _mm256_loadu_pd(p[6] + offset), d1 = _mm256_loadu_pd(p[7] + offset);
    transpose4(a0, b0, c0, d0);
    transpose4(a1, b1, c1, d1);
    a = join(a0, a1);
    b = join(b0, b1);
    c = join(c0, c1);
    d = join(d0, d1);
  }
  // out[lane][0..7] = the eight values of that lane: an 8x8 transpose in four 4x4 blocks.
  [[gnu::always_inline]] static void store_lanes8(double (*out)[8], T a0, T a1, T a2, T a3, T a4,
                                                  T a5, T a6, T a7) {
    const T in[8] = {a0, a1, a2, a3, a4, a5, a6, a7};
    for (int half = 0; half < 2; ++half) {      // lanes 0-3, then 4-7
      for (int block = 0; block < 2; ++block) {  // values 0-3, then 4-7
        __m256d r[4];
        for (int i = 0; i < 4; ++i) {
          const V8d v = in[4 * block + i];
          r[i] = half == 0 ? low_half(v) : high_half(v);
        }
        transpose4(r[0], r[1], r[2], r[3]);
        for (int l = 0; l < 4; ++l) _mm256_store_pd(out[4 * half + l] + 4 * block, r[l]);
      }
    }
  }
  // acc is a 64-byte aligned accumulator record.
  [[gnu::always_inline]] static void add8(double* acc, const double* v) {
    _mm512_store_pd(acc, _mm512_add_pd(_mm512_load_pd(acc), _mm512_load_pd(v)));
  }
  [[gnu::always_inline]] static void sub8(double* acc, const double* v) {
    _mm512_store_pd(acc, _mm512_sub_pd(_mm512_load_pd(acc), _mm512_load_pd(v)));
  }
};

}  // namespace

void pair_batch_avx512(const PairBatchArgs& args, const std::uint32_t* pairs, const double* scale,
                       std::size_t n, PairBatchStats& stats) {
  lanes::pair_batch<Avx512Ops>(args, pairs, scale, n, stats);
}

void wall_batch_avx512(const WallBatchArgs& args, const WallBatch& batch) {
  lanes::wall_batch<Avx512Ops>(args, batch);
}

}  // namespace seedcal
#else
namespace seedcal {
// Not built for AVX-512: pair_batch_avx512_usable() is false and this is never called.
void pair_batch_avx512(const PairBatchArgs& args, const std::uint32_t* pairs, const double* scale,
                       std::size_t n, PairBatchStats& stats) {
  pair_batch_scalar(args, pairs, scale, n, stats);
}
void wall_batch_avx512(const WallBatchArgs& args, const WallBatch& batch) {
  wall_batch_scalar(args, batch);
}
}  // namespace seedcal
#endif
