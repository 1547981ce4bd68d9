// The four-lane batch kernel (sim/pair_batch.hpp). Built with -mavx2 and without FMA contraction
// (solver/CMakeLists.txt); called only where pair_batch_avx2_usable(). Everything but the entry
// point has internal linkage, so no AVX2 code can stand in for a baseline function at link time.
#include "solver/sim/pair_batch_lanes.hpp"

#ifdef __AVX2__
#include <immintrin.h>

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
};

}  // namespace

void pair_batch_avx2(const PairBatchArgs& args, const std::uint32_t* pairs, const double* scale,
                     std::size_t n, PairBatchStats& stats) {
  lanes::pair_batch_lanes<Avx2Ops>(args, pairs, scale, n, stats);
}

}  // namespace seedcal
#else
namespace seedcal {
// Not built for AVX2: pair_batch_avx2_usable() is false and this is never called.
void pair_batch_avx2(const PairBatchArgs& args, const std::uint32_t* pairs, const double* scale,
                     std::size_t n, PairBatchStats& stats) {
  pair_batch_scalar(args, pairs, scale, n, stats);
}
}  // namespace seedcal
#endif
