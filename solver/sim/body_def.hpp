#pragma once
// What it takes to add one rigid body: its spheres in the principal frame, mass properties (from
// the union of the spheres, computed by the clump builder or, for one sphere, analytically) and
// its initial pose and motion.
#include <cstdint>
#include <vector>

#include "solver/core/vec.hpp"

namespace seedcal {

struct SphereDef {
  Vec3 offset_m = Vec3::Zero();  // centre in the body's principal frame (centre of mass at 0)
  double radius_m = 0.0;
};

struct BodyDef {
  std::vector<SphereDef> spheres;
  std::uint16_t material = 0;
  double mass_kg = 0.0;
  Vec3 principal_inertia_kg_m2 = Vec3::Zero();
  Vec3 position_m = Vec3::Zero();
  Quat orientation = Quat::Identity();
  Vec3 velocity_m_s = Vec3::Zero();
  Vec3 angular_velocity_rad_s = Vec3::Zero();
};

// A solid sphere: m = rho 4/3 pi r^3, I = 2/5 m r^2.
BodyDef sphere_body(double radius_m, double density_kg_m3, std::uint16_t material);

}  // namespace seedcal
