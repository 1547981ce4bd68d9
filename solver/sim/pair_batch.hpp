#pragma once
// The sphere-sphere force kernel for a batch of touching pairs, and its sphere-wall twin: the
// contact law (contact/contact_law.hpp, any normal and rolling model) on one lane
// (pair_batch_scalar.cpp, any x86-64),
// four (pair_batch_avx2.cpp, AVX2) or eight (pair_batch_avx512.cpp, AVX-512F), chosen once per
// run. All give the same bits: the lanes run the same operations in the same order without fused
// multiply-adds, and the results are added to the bodies in the order of the batch (tested in
// tests/physics/determinism_test.cpp).
//
// This header holds only plain types: the AVX2 and AVX-512 translation units must not include Eigen
// or other library headers whose inline functions they would compile for their instruction set
// (sim/contact_view.hpp checks the layouts below against the real records).
#include <cstddef>
#include <cstdint>

#include "solver/contact/model_kinds.hpp"

namespace seedcal {

// Offsets, in doubles, of the fields of the packed views.
namespace view_layout {
inline constexpr int kSphereStride = 4;  // SphereView
inline constexpr int kSpherePosition = 0, kSphereRadius = 3;
inline constexpr int kBodyStride = 16;  // BodyView
inline constexpr int kBodyVelocity = 0, kBodyOmega = 3, kBodyVelocityEnd = 6, kBodyOmegaEnd = 9,
                     kBodyInvMass = 12, kBodyPosition = 13;
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
  const std::uint32_t* sphere_body = nullptr;      // each sphere's body
  const std::uint16_t* sphere_material = nullptr;  // each sphere's material
  const double* bodies = nullptr;   // BodyView records
  double* accumulators = nullptr;   // this thread's BodyAccumulator records
  std::uint8_t* touched = nullptr;  // this thread's marks of the accumulators it wrote
  const BatchPairConstants* pair_constants = nullptr;  // [material_i * materials + material_j]
  std::size_t materials = 0;
  // Every sphere pair's constants when all spheres are of one material (broadcast to the lanes
  // instead of gathered); null otherwise.
  const BatchPairConstants* uniform_constants = nullptr;
  const std::uint32_t* si = nullptr;  // neighbour list: sphere i of pair k
  const std::uint32_t* sj = nullptr;
  double* tangential_m = nullptr;  // 3 doubles per pair: the tangential spring
  double* rolling_m = nullptr;     // EPSD: 3 doubles per pair, the rolling spring moment (N m)
  const double* body_mass_kg = nullptr;           // EPSD: each body's mass
  const double* body_inertia_kg_m2 = nullptr;     // EPSD: each body's principal inertia (3)
  double dt_s = 0.0;
  bool clip_attractive = false;
  RollingModel rolling = RollingModel::none;
  bool cdt_lever_from_centre_of_mass = false;
  double epsd_damping_ratio = 0.0;
  const double* overlap_limit_m = nullptr;  // each sphere's deepest allowed overlap (guards)
  // The dashpots read the body views' end-of-step velocities (ContactOptions::dashpot_predicted);
  // otherwise those equal the half-step ones and the kernel neither loads nor combines them.
  bool end_velocities = true;
};

// The contacts deep enough for the overlap guard to look up their limit (past the prefilter,
// overlap_prefilter_fraction x the smaller radius): the largest overlap / limit (above 1 the guard
// trips) with that pair's body, overlap, smaller radius and limit, and the largest overlap /
// smaller radius (Simulation::deepest_overlap_fraction).
struct DeepOverlap {
  double worst_ratio = 0.0, worst_overlap_m = 0.0, worst_radius_m = 0.0, worst_limit_m = 0.0;
  double deepest_fraction = 0.0;
  std::int64_t worst_body = -1;

  void note(double overlap, double r_min, double limit, std::int64_t body) {
    const double fraction = overlap / r_min;
    if (fraction > deepest_fraction) deepest_fraction = fraction;
    const double ratio = overlap / limit;
    if (ratio > worst_ratio) *this = {ratio, overlap, r_min, limit, deepest_fraction, body};
  }
  // Another share's record; on a tie the lower body wins, so the record does not depend on how
  // the work was split.
  void merge(const DeepOverlap& o) {
    const double deepest = deepest_fraction > o.deepest_fraction ? deepest_fraction : o.deepest_fraction;
    if (o.worst_ratio > worst_ratio ||
        (o.worst_ratio == worst_ratio && o.worst_body >= 0 && (worst_body < 0 || o.worst_body < worst_body)))
      *this = o;
    deepest_fraction = deepest;
  }
};

// What ThreadStats::note() records, gathered over a batch.
struct PairBatchStats {
  double max_overlap_m = 0.0, max_fn_n = 0.0;
  double prefilter = 0.5;  // overlap / smaller radius past which a pair's limit is looked up
  DeepOverlap deep;
};

// One touching sphere-wall contact, as the contact kernel's wall pass hands it to the wall batch
// kernel: 16 doubles, so each lane's record loads four fields at a time.
struct alignas(64) WallContactIn {
  double normal[3];              // unit, from the sphere centre towards the wall (world)
  double overlap_m;
  double lever_m[3];             // contact point minus the body's centre of mass
  double radius_m;               // R*: the sphere's radius (the wall's is infinite)
  double wall_velocity_m_s[3];   // the wall's material velocity at the contact point
  double mass_kg;                // m*: the body's mass (the wall's is infinite)
  double rolling_lever_m;        // CDT: the lever R_i of the capacity mu_r |Fn| R_i
  double spare;                  // keeps the record at 16 doubles
  std::uint32_t body;            // BodyView record
  std::uint32_t constants;       // index of the material pair in pair_constants
  std::uint64_t pair;            // index in the wall contact list: its tangential spring
};

// What the wall batch kernel returns for one contact.
struct WallContactOut {
  double force_on_sphere_n[3];  // the wall receives the opposite
  double torque_n_m[3];         // of that force about the body's centre of mass
  double roll_capacity_n_m;     // CDT capacity mu_r |Fn| R_i (0 without CDT)
  double normal_force_n;        // signed, positive = repulsive
  double normal_stiffness_n_m;  // Sn
  double rolling_torque_n_m[3]; // EPSD: on the sphere's body; the wall receives the opposite
};

// EPSD only: what the rolling spring of a sphere-wall contact needs beyond WallContactIn.
struct WallRollingIn {
  double wall_spin_rad_s[3];     // the wall's angular velocity (world)
  double rolling_inertia_kg_m2;  // I_r: the body's about the contact point (rolling_epsd.hpp)
};

struct WallBatchArgs {
  const double* bodies = nullptr;                      // BodyView records
  const BatchPairConstants* pair_constants = nullptr;
  double* tangential_m = nullptr;                      // the wall contact list's springs
  double* rolling_m = nullptr;                         // EPSD: its rolling springs
  double dt_s = 0.0;
  bool clip_attractive = false;
  RollingModel rolling = RollingModel::none;
  double epsd_damping_ratio = 0.0;
  bool end_velocities = true;  // as PairBatchArgs::end_velocities
};

// One batch of touching sphere-wall contacts: in[0..n) with damping scale scale[i] (1, or HMNR's
// 1/sqrt(touching pairs of the body and wall)) and, for EPSD, rolling[0..n).
struct WallBatch {
  const WallContactIn* in = nullptr;
  const double* scale = nullptr;
  const WallRollingIn* rolling = nullptr;
  std::size_t n = 0;
  WallContactOut* out = nullptr;
};

// The contact law of a batch's contacts, springs updated in place; results in out[0..n). The
// caller adds them to bodies and walls in order.
using WallBatchFn = void (*)(const WallBatchArgs& args, const WallBatch& batch);
void wall_batch_scalar(const WallBatchArgs& args, const WallBatch& batch);
void wall_batch_avx2(const WallBatchArgs& args, const WallBatch& batch);
void wall_batch_avx512(const WallBatchArgs& args, const WallBatch& batch);
WallBatchFn choose_wall_batch(int max_lanes);

// Forces of the touching pairs pairs[0..n) of the neighbour list (every one must touch), with
// damping scale scale[i] (HMNR's 1/sqrt(contacts); null: 1 for every pair, as Hertz-Mindlin's);
// added to the accumulators in that order.
using PairBatchFn = void (*)(const PairBatchArgs& args, const std::uint32_t* pairs,
                             const double* scale, std::size_t n, PairBatchStats& stats);

void pair_batch_scalar(const PairBatchArgs& args, const std::uint32_t* pairs, const double* scale,
                       std::size_t n, PairBatchStats& stats);
// Four lanes; only where pair_batch_avx2_usable().
void pair_batch_avx2(const PairBatchArgs& args, const std::uint32_t* pairs, const double* scale,
                     std::size_t n, PairBatchStats& stats);
// Eight lanes; only where pair_batch_avx512_usable().
void pair_batch_avx512(const PairBatchArgs& args, const std::uint32_t* pairs, const double* scale,
                       std::size_t n, PairBatchStats& stats);
// The AVX2 kernel was built and this CPU runs AVX2.
bool pair_batch_avx2_usable();
// The AVX-512 kernel was built and this CPU runs AVX-512F.
bool pair_batch_avx512_usable();
// The lanes of the widest kernel this CPU runs, at most max_lanes (1, 4 or 8).
int pair_batch_lanes_used(int max_lanes);
// That kernel.
PairBatchFn choose_pair_batch(int max_lanes);

}  // namespace seedcal
