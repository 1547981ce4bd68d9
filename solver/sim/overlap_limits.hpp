#pragma once
// The deepest overlap each sphere may take before the overlap guard stops a run (sim/guards.hpp,
// docs/contact_models.md "The overlap guard"): a contact takes the smaller of its two spheres'
// limits; a sphere-wall contact the sphere's.
#include <vector>

#include "solver/core/body_state.hpp"
#include "solver/core/materials.hpp"
#include "solver/sim/guards.hpp"

namespace seedcal {

// Per sphere, m: for the sphere of a one-sphere body, max_overlap_fraction x its radius; for a
// sphere of a clump, the smaller of max_clump_sphere_overlap_fraction x its own radius and
// max_overlap_fraction x the body's reference radius. The reference radius is the body's
// volume-equivalent radius, (3 m / (4 pi rho))^(1/3) with rho its spheres' material density, and
// never less than its largest sphere (a body given a mass below its spheres' volume). So every
// limit is at least min(max_overlap_fraction, max_clump_sphere_overlap_fraction) x the radius,
// the cheap test the contact kernels make before they look a limit up.
std::vector<double> sphere_overlap_limits(const BodyState& bodies, const SphereState& spheres,
                                          const std::vector<Material>& materials,
                                          const GuardOptions& guards);

// The fraction of a sphere's radius no limit goes below.
double overlap_prefilter_fraction(const GuardOptions& guards);

}  // namespace seedcal
