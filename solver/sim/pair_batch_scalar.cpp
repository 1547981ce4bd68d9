// The one-lane batch kernel (sim/pair_batch.hpp), for any x86-64, and the choice between the
// kernels.
#include "solver/sim/pair_batch_lanes.hpp"

namespace seedcal {

void pair_batch_scalar(const PairBatchArgs& args, const std::uint32_t* pairs, const double* scale,
                       std::size_t n, PairBatchStats& stats) {
  lanes::pair_batch<lanes::ScalarOps>(args, pairs, scale, n, stats);
}

void wall_batch_scalar(const WallBatchArgs& args, const WallBatch& batch) {
  lanes::wall_batch<lanes::ScalarOps>(args, batch);
}

bool pair_batch_avx2_usable() {
#if defined(SEEDCAL_PAIR_BATCH_AVX2) && (defined(__x86_64__) || defined(__i386__))
  return __builtin_cpu_supports("avx2");
#else
  return false;
#endif
}

bool pair_batch_avx512_usable() {
#if defined(SEEDCAL_PAIR_BATCH_AVX512) && (defined(__x86_64__) || defined(__i386__))
  return __builtin_cpu_supports("avx512f");
#else
  return false;
#endif
}

int pair_batch_lanes_used(int max_lanes) {
  if (max_lanes >= 8 && pair_batch_avx512_usable()) return 8;
  if (max_lanes >= 4 && pair_batch_avx2_usable()) return 4;
  return 1;
}

namespace {
// The kernel of the widest width this CPU runs, at most max_lanes.
template <class Fn>
Fn widest(int max_lanes, Fn eight, Fn four, Fn one) {
  const int lanes = pair_batch_lanes_used(max_lanes);
  return lanes == 8 ? eight : lanes == 4 ? four : one;
}
}  // namespace

PairBatchFn choose_pair_batch(int max_lanes) {
  return widest<PairBatchFn>(max_lanes, &pair_batch_avx512, &pair_batch_avx2, &pair_batch_scalar);
}

WallBatchFn choose_wall_batch(int max_lanes) {
  return widest<WallBatchFn>(max_lanes, &wall_batch_avx512, &wall_batch_avx2, &wall_batch_scalar);
}

}  // namespace seedcal
