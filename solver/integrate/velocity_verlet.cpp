#include "solver/integrate/velocity_verlet.hpp"

#include <algorithm>
#include <cmath>

#include "solver/integrate/free_rotation.hpp"

namespace seedcal {

namespace {
// Sphere i of body b at the body's pose (world centre): x_b + R(q) offset_i. The rotation matrix
// is formed once per body (sphere_rotation) and applied to each of its spheres: for a clump that
// is 15 flops per sphere against about 30 for rotating by the quaternion itself.
inline Mat3 sphere_rotation(const Quat& q) { return q.toRotationMatrix(); }
inline Vec3 sphere_centre(const Vec3& body_position, const Mat3& rotation, const Vec3& offset) {
  return offset.isZero(0.0) ? body_position : Vec3(body_position + rotation * offset);
}

// Body b's translation and momentum for a step: the last step's second half kick when pending
// (the same operations as finish_kick()), then velocity Verlet's first half: kick with the same
// forces, drift. Stores and returns the new momentum; a non-finite position, velocity or momentum
// lowers `bad` to b.
[[gnu::always_inline]] inline Vec3 kick_drift(
    std::size_t b, bool kick, double hk, double h, double dt, Vec3* __restrict pos,
    Vec3* __restrict vel, Vec3* __restrict mom, const Vec3* __restrict force,
    const Vec3* __restrict torque, const double* __restrict inv_mass, std::int64_t& bad) {
  Vec3 v_full = vel[b], L_full = mom[b];
  if (kick) {
    v_full = v_full + (hk * inv_mass[b]) * force[b];
    L_full = L_full + hk * torque[b];
  }
  const Vec3 v = v_full + (h * inv_mass[b]) * force[b];
  const Vec3 L = L_full + h * torque[b];
  const Vec3 p = pos[b] + dt * v;
  if (!std::isfinite(p.sum() + v.sum() + L.sum())) bad = std::min(bad, static_cast<std::int64_t>(b));
  vel[b] = v;
  mom[b] = L;
  pos[b] = p;
  return L;
}

// kick_drift(), then the rotation over the step.
[[gnu::always_inline]] inline void kick_drift_rotate(
    std::size_t b, bool iso, bool kick, double hk, double h, double dt, Vec3* __restrict pos,
    Quat* __restrict rot, Vec3* __restrict vel, Vec3* __restrict mom, const Vec3* __restrict force,
    const Vec3* __restrict torque, const double* __restrict inv_mass,
    const Vec3* __restrict inv_inertia, std::int64_t& bad) {
  const Vec3 L = kick_drift(b, kick, hk, h, dt, pos, vel, mom, force, torque, inv_mass, bad);
  Quat q = rot[b];
  free_rotation_step(q, L, inv_inertia[b], iso, dt);
  rot[b] = q;
}

// A lone sphere at its body's centre of mass: kick_drift(), views and skin check as for any body,
// the same operations in the same order, without the orientation (which moves no sphere of it) and
// the offset: 64 bytes a body and step fewer to stream through a bed larger than the cache, with
// the same bits (docs/results/solver_speed.md).
[[gnu::always_inline]] inline void lone_sphere_step(
    std::size_t b, bool kick, double hk, double h, double hp, double dt, Vec3* __restrict pos,
    Vec3* __restrict vel, Vec3* __restrict mom, Vec3* __restrict omega,
    const Vec3* __restrict force, const Vec3* __restrict torque,
    const double* __restrict inv_mass, const Vec3* __restrict inv_inertia, std::uint32_t i,
    const double* __restrict radius, Vec3* __restrict centre, BodyView* __restrict bview, SphereView* __restrict sview,
    const Vec3* __restrict ref, double& max_moved_sq, std::int64_t& bad) {
  const Vec3 L = kick_drift(b, kick, hk, h, dt, pos, vel, mom, force, torque, inv_mass, bad);
  const Vec3 v = vel[b], p = pos[b], T = torque[b];
  const double ii = inv_inertia[b].x();
  const Vec3 w = L * ii;
  omega[b] = w;
  // Without the predicted dashpot velocity (hp = 0) the end velocity is w itself.
  fill_body_view(bview[b], v, w, hp == 0.0 ? w : Vec3(Vec3(L + hp * T) * ii), force[b],
                 inv_mass[b], hp, p);
  centre[i] = p;
  fill_sphere_view(sview[i], p, radius[i]);
  if (ref) max_moved_sq = std::max(max_moved_sq, (p - ref[i]).squaredNorm());
}

}  // namespace

void move_bodies(BodyState& bodies, SphereState& spheres, BodyView* body_view,
                 SphereView* sphere_view, std::size_t b_begin, std::size_t b_end,
                 const VerletPass& pass, const Vec3* ref, double& max_moved_sq, std::int64_t& bad) {
  const double dt = pass.dt_s;
  const bool kick = pass.kick;
  const double hk = pass.kick_half_s;
  const double h = 0.5 * dt;
  const double hp = pass.predict_s;
  // Raw pointers: the stores to the views must not make the compiler reload the state.
  Vec3* __restrict pos = bodies.position_m.data();
  Quat* __restrict rot = bodies.orientation.data();
  Vec3* __restrict vel = bodies.velocity_m_s.data();
  Vec3* __restrict mom = bodies.angular_momentum.data();
  Vec3* __restrict omega = bodies.angular_velocity.data();
  const Vec3* __restrict force = bodies.force_n.data();
  const Vec3* __restrict torque = bodies.torque_n_m.data();
  const double* __restrict inv_mass = bodies.inv_mass.data();
  const Vec3* __restrict inv_inertia = bodies.inv_inertia.data();
  const std::uint8_t* __restrict iso_flag = bodies.isotropic.data();
  const std::uint32_t* __restrict first = bodies.first_sphere.data();
  const Vec3* __restrict offset = spheres.offset_body_m.data();
  const double* __restrict radius = spheres.radius_m.data();
  Vec3* __restrict centre = spheres.position_m.data();
  BodyView* __restrict bview = body_view;
  SphereView* __restrict sview = sphere_view;
  // Blocks of bodies, each in two passes: the kick, drift and rotation of the block's clumps,
  // then the views and spheres of all its bodies (a sphere's kick, drift and rotation there). A
  // clump's rotation is a chain of dependent operations (integrate/free_rotation.hpp); in a short
  // first loop the processor overlaps the chains of several clumps, which one loop doing each
  // body's rotation and spheres together would not let it do (docs/results/solver_speed.md). A
  // block stays in the first-level cache between the passes; spheres stay in one pass, where a
  // second costs more than it saves.
  constexpr std::size_t kBlock = 32;
  for (std::size_t b_block = b_begin; b_block < b_end; b_block += kBlock) {
    const std::size_t block_end = std::min(b_end, b_block + kBlock);
    for (std::size_t b = b_block; b < block_end; ++b)
      if (iso_flag[b] == 0)
        kick_drift_rotate(b, false, kick, hk, h, dt, pos, rot, vel, mom, force, torque, inv_mass,
                          inv_inertia, bad);
    for (std::size_t b = b_block; b < block_end; ++b) {
      if (iso_flag[b] == 2) {
        lone_sphere_step(b, kick, hk, h, hp, dt, pos, vel, mom, omega, force, torque, inv_mass,
                         inv_inertia, first[b], radius, centre, bview, sview, ref,
                         max_moved_sq, bad);
        continue;
      }
      const bool iso = iso_flag[b] != 0;
      if (iso)  // a short rotation: no chain to overlap
        kick_drift_rotate(b, true, kick, hk, h, dt, pos, rot, vel, mom, force, torque, inv_mass,
                          inv_inertia, bad);
      const Vec3 v = vel[b], L = mom[b], p = pos[b];
      const Quat q = rot[b];
      const Vec3 w = angular_velocity_from_momentum(q, inv_inertia[b], L, iso);
      omega[b] = w;
      // Without the predicted dashpot velocity (hp = 0) the end velocity is w itself: the second
      // rotation of the momentum into the world frame is skipped.
      fill_body_view(bview[b], v, w,
                     hp == 0.0 ? w
                               : angular_velocity_from_momentum(q, inv_inertia[b],
                                                                Vec3(L + hp * torque[b]), iso),
                     force[b], inv_mass[b], hp, p);
      // The rotation matrix only when some sphere is off the centre of mass (not for a lone
      // sphere).
      Mat3 rotation;
      bool rotated = false;
      for (std::uint32_t i = first[b]; i < first[b + 1]; ++i) {
        if (!rotated && !offset[i].isZero(0.0)) {
          rotation = sphere_rotation(q);
          rotated = true;
        }
        const Vec3 c = rotated ? sphere_centre(p, rotation, offset[i]) : p;
        centre[i] = c;
        fill_sphere_view(sview[i], c, radius[i]);
        if (ref) max_moved_sq = std::max(max_moved_sq, (c - ref[i]).squaredNorm());
      }
    }
  }
}

void finish_half_kick(BodyState& bodies, double hk, int threads) {
  const std::size_t nb = bodies.size();
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
  for (std::size_t b = 0; b < nb; ++b) {
    const Vec3 L = bodies.angular_momentum[b] + hk * bodies.torque_n_m[b];
    bodies.velocity_m_s[b] += (hk * bodies.inv_mass[b]) * bodies.force_n[b];
    bodies.angular_momentum[b] = L;
    bodies.angular_velocity[b] = angular_velocity_from_momentum(
        bodies.orientation[b], bodies.inv_inertia[b], L, bodies.isotropic[b] != 0);
  }
}

void place_spheres(const BodyState& bodies, SphereState& spheres, int threads) {
  const std::size_t n = spheres.size();
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t b = spheres.body[i];
    spheres.position_m[i] = sphere_centre(
        bodies.position_m[b], sphere_rotation(bodies.orientation[b]), spheres.offset_body_m[i]);
  }
}

}  // namespace seedcal
