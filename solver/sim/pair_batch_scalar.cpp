// The one-lane batch kernel (sim/pair_batch.hpp), for any x86-64, and the choice between the
// kernels.
#include "solver/sim/pair_batch_lanes.hpp"

namespace seedcal {

void pair_batch_scalar(const PairBatchArgs& args, const std::uint32_t* pairs, const double* scale,
                       std::size_t n, PairBatchStats& stats) {
  lanes::pair_batch_lanes<lanes::ScalarOps>(args, pairs, scale, n, stats);
}

void wall_batch_scalar(const WallBatchArgs& args, const WallContactIn* in, std::size_t n,
                       WallContactOut* out) {
  lanes::wall_batch_lanes<lanes::ScalarOps>(args, in, n, out);
}

bool pair_batch_avx2_usable() {
#if defined(SEEDCAL_PAIR_BATCH_AVX2) && (defined(__x86_64__) || defined(__i386__))
  return __builtin_cpu_supports("avx2");
#else
  return false;
#endif
}

PairBatchFn choose_pair_batch(bool allow_simd) {
  return allow_simd && pair_batch_avx2_usable() ? &pair_batch_avx2 : &pair_batch_scalar;
}

WallBatchFn choose_wall_batch(bool allow_simd) {
  return allow_simd && pair_batch_avx2_usable() ? &wall_batch_avx2 : &wall_batch_scalar;
}

}  // namespace seedcal
