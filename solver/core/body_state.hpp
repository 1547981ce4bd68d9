#pragma once
// Rigid-body and sphere state as structure-of-arrays (DESIGN.md, "The solver").
//
// Every particle is a rigid body (a plain sphere is a one-sphere clump). Bodies carry translational
// state at the centre of mass and rotational state in the principal frame: q maps body (principal)
// coordinates to world coordinates; angular momentum is kept in the world frame, which a free body
// conserves exactly, and the world angular velocity is cached after every update.
#include <cstdint>
#include <vector>

#include "solver/core/vec.hpp"

namespace seedcal {

struct BodyState {
  std::vector<Vec3> position_m;            // centre of mass, world
  std::vector<Quat> orientation;           // principal frame -> world (kept as given for a lone
                                           // sphere at the centre of mass: it moves nothing)
  std::vector<Vec3> velocity_m_s;          // centre-of-mass velocity, world
  std::vector<Vec3> angular_momentum;      // world frame, kg m2/s
  std::vector<Vec3> angular_velocity;      // world frame, rad/s (derived, cached)
  std::vector<double> mass_kg;
  std::vector<double> inv_mass;
  std::vector<Vec3> principal_inertia;     // kg m2, body frame
  std::vector<Vec3> inv_inertia;           // 1 / principal_inertia
  std::vector<std::uint8_t> isotropic;     // 1 when the three principal moments are equal,
                                           // 2 when moreover the body is one sphere at its centre
                                           // of mass (its step skips the orientation)
  std::vector<std::uint32_t> first_sphere; // spheres of body b: [first_sphere[b], first_sphere[b+1])
  std::vector<std::uint32_t> id;           // the id add_body() returned (bodies are re-sorted
                                           // in space for cache locality; ids stay)
  std::vector<Vec3> force_n;               // accumulated this step, world
  std::vector<Vec3> torque_n_m;            // about the centre of mass, world

  std::size_t size() const { return position_m.size(); }
};

struct SphereState {
  std::vector<std::uint32_t> body;     // owning body
  std::vector<Vec3> offset_body_m;     // centre in the body's principal frame
  std::vector<double> radius_m;
  std::vector<std::uint16_t> material; // index into the material table
  std::vector<Vec3> position_m;        // world centre (derived each step)

  std::size_t size() const { return radius_m.size(); }
};

// World angular velocity from world angular momentum: w = R I^-1 R^T L.
inline Vec3 angular_velocity_from_momentum(const Quat& q, const Vec3& inv_inertia, const Vec3& L,
                                           bool isotropic) {
  if (isotropic) return L * inv_inertia.x();
  const Vec3 pi = q.conjugate() * L;
  return q * Vec3(pi.cwiseProduct(inv_inertia));
}

// World angular momentum from world angular velocity: L = R I R^T w.
inline Vec3 angular_momentum_from_velocity(const Quat& q, const Vec3& inertia, const Vec3& w) {
  const Vec3 wb = q.conjugate() * w;
  return q * Vec3(wb.x() * inertia.x(), wb.y() * inertia.y(), wb.z() * inertia.z());
}

}  // namespace seedcal
