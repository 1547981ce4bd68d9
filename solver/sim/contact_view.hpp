#pragma once
// Packed per-step copies of what the contact kernel reads and writes: a half-line record per
// sphere, a two-line record per body.
//
// The state itself is kept as structure-of-arrays (core/body_state.hpp): the integrator streams
// through one field at a time. The contact kernel instead visits two bodies per pair in
// neighbour-list order and needs about ten fields of each. Read from the separate arrays, that is
// one cache line per field and body; from these records it is one line per sphere, two per body
// and one per accumulator. The records are refreshed in the integrator's body pass, which already
// has every field in registers, so they cost one streaming write per body and step. The
// arithmetic on them is the same as on the arrays: results do not change.
//
// Only what changes every step is in them. A sphere's body and material never change between
// spatial sorts and are read from the sphere arrays (core/sphere_state.hpp), which no core writes
// while the others read them; the lever arms take the body's centre from its body record. So a
// clump's spheres take half a line each, not a line: half the bytes through the body pass, and
// half the lines that move between the cores for the bodies next to the threads' split (a line
// that one core writes and another reads crosses twice a step; tests/bench/README.md).
#include <cstddef>
#include <cstdint>

#include "solver/sim/pair_batch.hpp"

#include "solver/core/vec.hpp"

namespace seedcal {

// One sphere, as the contact kernel sees it (32 bytes: two to a cache line).
struct alignas(32) SphereView {
  Vec3 position_m;  // world centre
  double radius_m;
};

// One body's velocities, as the contact kernel sees it (two cache lines).
struct alignas(64) BodyView {
  Vec3 velocity_m_s;          // half-step velocity (spring increments)
  Vec3 angular_velocity;      // half-step angular velocity, world
  Vec3 velocity_end_m_s;      // predicted end-of-step velocity (dashpots)
  Vec3 angular_velocity_end;  // predicted end-of-step angular velocity, world
  double inv_mass;            // 1/kg
  Vec3 position_m;            // centre of mass (contact lever arms)
};

// One body's share of the contact forces, accumulated by one thread (64 bytes).
struct alignas(64) BodyAccumulator {
  Vec3 force_n;
  Vec3 torque_n_m;
  double roll_capacity_n_m;  // CDT: sum mu_r |Fn| R_i over the body's contacts
};

// One wall's share of the contact forces, accumulated by one thread (64 bytes, so that two
// threads never write to one cache line).
struct alignas(64) WallAccumulator {
  Vec3 force_n;                       // on the wall
  Vec3 torque_n_m;                    // about the wall frame's origin
  double contact_stiffness_n_m = 0.0; // summed normal stiffness of its contacts
  int contacts = 0;
};

// A body's record: half-step velocities and, for the dashpots, v~ = v + h F / m with the given
// predicted angular velocity w~ (h = 0: the half-step ones; contact/contact_law.hpp); the centre of
// mass.
inline void fill_body_view(BodyView& bv, const Vec3& v, const Vec3& w, const Vec3& w_end,
                           const Vec3& force, double inv_mass, double h, const Vec3& position) {
  bv.velocity_m_s = v;
  bv.angular_velocity = w;
  bv.velocity_end_m_s = h == 0.0 ? v : Vec3(v + (h * inv_mass) * force);
  bv.angular_velocity_end = w_end;
  bv.inv_mass = inv_mass;
  bv.position_m = position;
}

// A sphere's record.
inline void fill_sphere_view(SphereView& sv, const Vec3& centre, double radius) {
  sv.position_m = centre;
  sv.radius_m = radius;
}

static_assert(sizeof(SphereView) == 32);
static_assert(sizeof(WallAccumulator) == 64);
static_assert(sizeof(BodyView) == 128);
static_assert(sizeof(BodyAccumulator) == 64);

// The batch kernel reads these records through the offsets of sim/pair_batch.hpp.
namespace view_layout_check {
namespace L = view_layout;
static_assert(sizeof(Vec3) == 3 * sizeof(double));
static_assert(sizeof(SphereView) == L::kSphereStride * sizeof(double));
static_assert(offsetof(SphereView, position_m) == L::kSpherePosition * sizeof(double));
static_assert(offsetof(SphereView, radius_m) == L::kSphereRadius * sizeof(double));
static_assert(sizeof(BodyView) == L::kBodyStride * sizeof(double));
static_assert(offsetof(BodyView, velocity_m_s) == L::kBodyVelocity * sizeof(double));
static_assert(offsetof(BodyView, angular_velocity) == L::kBodyOmega * sizeof(double));
static_assert(offsetof(BodyView, velocity_end_m_s) == L::kBodyVelocityEnd * sizeof(double));
static_assert(offsetof(BodyView, angular_velocity_end) == L::kBodyOmegaEnd * sizeof(double));
static_assert(offsetof(BodyView, inv_mass) == L::kBodyInvMass * sizeof(double));
static_assert(offsetof(BodyView, position_m) == L::kBodyPosition * sizeof(double));
static_assert(sizeof(BodyAccumulator) == L::kAccStride * sizeof(double));
static_assert(offsetof(BodyAccumulator, force_n) == L::kAccForce * sizeof(double));
static_assert(offsetof(BodyAccumulator, torque_n_m) == L::kAccTorque * sizeof(double));
static_assert(offsetof(BodyAccumulator, roll_capacity_n_m) == L::kAccRollCapacity * sizeof(double));
}  // namespace view_layout_check

}  // namespace seedcal
