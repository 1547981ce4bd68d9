#pragma once
// The 4x4 transpose of four-double rows that the four- and eight-lane batch kernels use to turn
// records into lanes and back. Included only by pair_batch_avx2.cpp and pair_batch_avx512.cpp, each
// built for its own instruction set: internal linkage, so neither unit's copy can stand in for the
// other's at link time.
#include <immintrin.h>

namespace seedcal {
namespace {

// V: __m256d or a GCC vector of four doubles (rows in, columns out).
template <class V>
[[gnu::always_inline]] inline void transpose4(V& a, V& b, V& c, V& d) {
  const __m256d t0 = _mm256_unpacklo_pd(a, b), t1 = _mm256_unpackhi_pd(a, b);
  const __m256d t2 = _mm256_unpacklo_pd(c, d), t3 = _mm256_unpackhi_pd(c, d);
  a = _mm256_permute2f128_pd(t0, t2, 0x20);
  b = _mm256_permute2f128_pd(t1, t3, 0x20);
  c = _mm256_permute2f128_pd(t0, t2, 0x31);
  d = _mm256_permute2f128_pd(t1, t3, 0x31);
}

}  // namespace
}  // namespace seedcal
