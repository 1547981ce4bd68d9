#pragma once
// The sphere-sphere force kernel for a batch of touching pairs (Hertz-Mindlin with or without
// HMNR, with no rolling friction or with CDT): the same code on one lane (pair_batch_scalar.cpp, any x86-64)
// or four (pair_batch_avx2.cpp, AVX2), chosen once per run. Both give the same bits: the lanes run
// the same operations in the same order without fused multiply-adds, and the results are added to
// the bodies in the order of the batch (tested in tests/physics/determinism_test.cpp).
//
// This header holds only plain types: the AVX2 translation unit must not include Eigen or other
// library headers whose inline functions it would compile for AVX2 (sim/contact_view.hpp checks
// the layouts below against the real records).
#include <cstddef>
#include <cstdint>

namespace seedcal {

// Offsets, in doubles (or bytes where named so), of the fields of the packed views.
namespace view_layout {
inline constexpr int kSphereStride = 8;  // SphereView
inline constexpr int kSpherePosition = 0, kSphereRadius = 3, kSphereBodyPosition = 4;
inline constexpr int kSphereBodyByte = 56, kSphereMaterialByte = 60;
inline constexpr int kBodyStride = 16;  // BodyView
inline constexpr int kBodyVelocity = 0, kBodyOmega = 3, kBodyVelocityEnd = 6, kBodyOmegaEnd = 9,
                     kBodyInvMass = 12;
inline constexpr int kAccStride = 8;  // BodyAccumulator
inline constexpr int kAccForce = 0, kAccTorque = 3, kAccRollCapacity = 6;
}  // namespace view_layout

// The constants of one material pair the kernel needs (from PairConstants).
struct BatchPairConstants {
  double e_star_pa = 0.0, beta = 0.0, static_friction = 0.0, rolling_friction = 0.0,
         sqrt_tangential_ratio = 0.0;
};

struct PairBatchArgs {
  const double* spheres = nullptr;  // SphereView records
  const double* bodies = nullptr;   // BodyView records
  double* accumulators = nullptr;   // this thread's BodyAccumulator records
  const BatchPairConstants* pair_constants = nullptr;  // [material_i * materials + material_j]
  std::size_t materials = 0;
  const std::uint32_t* si = nullptr;  // neighbour list: sphere i of pair k
  const std::uint32_t* sj = nullptr;
  double* tangential_m = nullptr;  // 3 doubles per pair: the tangential spring
  double dt_s = 0.0;
  bool clip_attractive = false;
  bool cdt = false;                // add mu_r |Fn| R_i to each body's rolling capacity
  bool cdt_lever_from_centre_of_mass = false;
};

// What ThreadStats::note() records, gathered over a batch.
struct PairBatchStats {
  double max_overlap_m = 0.0, max_fn_n = 0.0;
  double ratio_limit = 0.5;  // overlap / smaller radius above which a pair is recorded
  double worst_ratio = 0.0, worst_radius_m = 0.0;
  std::int64_t worst_body = -1;
};

// Forces of the touching pairs pairs[0..n) of the neighbour list (every one must touch), with
// damping scale scale[i] (1, or HMNR's 1/sqrt(contacts)); added to the accumulators in that order.
using PairBatchFn = void (*)(const PairBatchArgs& args, const std::uint32_t* pairs,
                             const double* scale, std::size_t n, PairBatchStats& stats);

void pair_batch_scalar(const PairBatchArgs& args, const std::uint32_t* pairs, const double* scale,
                       std::size_t n, PairBatchStats& stats);
// Four lanes; only where pair_batch_avx2_usable().
void pair_batch_avx2(const PairBatchArgs& args, const std::uint32_t* pairs, const double* scale,
                     std::size_t n, PairBatchStats& stats);
// The AVX2 kernel was built and this CPU runs AVX2.
bool pair_batch_avx2_usable();
// The four-lane kernel where usable and wanted, else the one-lane one.
PairBatchFn choose_pair_batch(bool allow_simd);

}  // namespace seedcal
