#pragma once
// Mass properties of a rigid clump from the union of its spheres (overlaps counted once), and the
// conversion of a clump given in any frame to a body in its principal frame.
#include <cstdint>
#include <vector>

#include "solver/core/vec.hpp"
#include "solver/sim/body_def.hpp"

namespace seedcal {

struct SphereXYZR {
  Vec3 centre_m;
  double radius_m;
};

struct UnionMassProperties {
  double volume_m3 = 0.0;
  Vec3 centroid_m = Vec3::Zero();         // in the input frame
  Mat3 inertia_unit_density = Mat3::Zero();  // about the centroid, input frame, for density 1
  Vec3 principal_moments_unit_density = Vec3::Zero();  // ascending
  Mat3 principal_axes = Mat3::Identity();  // columns: principal axes in the input frame (det +1)
  double volume_rel_error_bound = 0.0;     // stated bound on |V - V_exact| / V
};

// Volume, centroid and inertia of the union of the spheres to the given relative tolerance.
UnionMassProperties union_mass_properties(const std::vector<SphereXYZR>& spheres,
                                          double rel_tolerance = 1e-4);

// A body from spheres given in an arbitrary frame placed at `frame_origin_m` with orientation
// `frame_orientation`: the body's centre of mass and principal frame come from the union.
BodyDef clump_body(const std::vector<SphereXYZR>& spheres, double density_kg_m3,
                   std::uint16_t material, const Vec3& frame_origin_m = Vec3::Zero(),
                   const Quat& frame_orientation = Quat::Identity(), double rel_tolerance = 1e-4);

}  // namespace seedcal
