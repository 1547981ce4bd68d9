// The four-lane batch kernel (sim/pair_batch.hpp). Built with -mavx2 and without FMA contraction
// (solver/CMakeLists.txt); called only where pair_batch_avx2_usable(). Everything but the entry
// point has internal linkage, so no AVX2 code can stand in for a baseline function at link time.
#include "solver/sim/pair_batch_lanes.hpp"

#ifdef __AVX2__
#include "solver/sim/pair_batch_transpose.hpp"

namespace seedcal {
namespace {

// Four doubles; __m256d itself carries may_alias, which a template argument would drop.
typedef double V4d __attribute__((vector_size(32)));

struct Avx2Ops {
  using T = V4d;
  static constexpr int lanes = 4;
  [[gnu::always_inline]] static T sqrt(T x) { return _mm256_sqrt_pd(x); }
  [[gnu::always_inline]] static T abs(T x) { return _mm256_andnot_pd(_mm256_set1_pd(-0.0), x); }
  template <class M>
  [[gnu::always_inline]] static bool any(M m) {
    return _mm256_movemask_pd(reinterpret_cast<__m256d>(m)) != 0;
  }
  [[gnu::always_inline]] static T splat(double x) { return _mm256_set1_pd(x); }
  [[gnu::always_inline]] static T gather(const double* const* p, int offset) {
    return _mm256_set_pd(p[3][offset], p[2][offset], p[1][offset], p[0][offset]);
  }
  [[gnu::always_inline]] static void store(double* out, T x) { _mm256_store_pd(out, x); }
  // Fields offset .. offset+3 of each lane's record, one vector per field.
  [[gnu::always_inline]] static void load4(const double* const* p, int offset, T& a, T& b, T& c,
                                           T& d) {
    a = _mm256_loadu_pd(p[0] + offset);
    b = _mm256_loadu_pd(p[1] + offset);
    c = _mm256_loadu_pd(p[2] + offset);
    d = _mm256_loadu_pd(p[3] + offset);
    transpose4(a, b, c, d);
  }
  // out[lane][0..7] = the eight values of that lane.
  [[gnu::always_inline]] static void store_lanes8(double (*out)[8], T a0, T a1, T a2, T a3, T a4,
                                                  T a5, T a6, T a7) {
    transpose4(a0, a1, a2, a3);
    transpose4(a4, a5, a6, a7);
    const T lo[4] = {a0, a1, a2, a3}, hi[4] = {a4, a5, a6, a7};
    for (int l = 0; l < 4; ++l) {
      _mm256_store_pd(out[l], lo[l]);
      _mm256_store_pd(out[l] + 4, hi[l]);
    }
  }
  // acc is a 64-byte aligned accumulator record.
  [[gnu::always_inline]] static void add8(double* acc, const double* v) {
    _mm256_store_pd(acc, _mm256_load_pd(acc) + _mm256_load_pd(v));
    _mm256_store_pd(acc + 4, _mm256_load_pd(acc + 4) + _mm256_load_pd(v + 4));
  }
  [[gnu::always_inline]] static void sub8(double* acc, const double* v) {
    _mm256_store_pd(acc, _mm256_load_pd(acc) - _mm256_load_pd(v));
    _mm256_store_pd(acc + 4, _mm256_load_pd(acc + 4) - _mm256_load_pd(v + 4));
  }
};

}  // namespace

void pair_batch_avx2(const PairBatchArgs& args, const std::uint32_t* pairs, const double* scale,
                     std::size_t n, PairBatchStats& stats) {
  lanes::pair_batch<Avx2Ops>(args, pairs, scale, n, stats);
}

void wall_batch_avx2(const WallBatchArgs& args, const WallBatch& batch) {
  lanes::wall_batch<Avx2Ops>(args, batch);
}

}  // namespace seedcal
#else
namespace seedcal {
// Not built for AVX2: pair_batch_avx2_usable() is false and this is never called.
void pair_batch_avx2(const PairBatchArgs& args, const std::uint32_t* pairs, const double* scale,
                     std::size_t n, PairBatchStats& stats) {
  pair_batch_scalar(args, pairs, scale, n, stats);
}
void wall_batch_avx2(const WallBatchArgs& args, const WallBatch& batch) {
  wall_batch_scalar(args, batch);
}
}  // namespace seedcal
#endif
