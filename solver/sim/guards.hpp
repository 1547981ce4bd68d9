#pragma once
// Stability guards: a run that goes wrong stops with the step, the body and the likely cause
// instead of writing NaN or exploding silently.
#include <cstdint>
#include <string>

namespace seedcal {

struct GuardOptions {
  // Deepest allowed overlap of a contact (docs/contact_models.md, "The overlap guard"). Hertz
  // theory assumes overlap << radius of curvature; past half a radius the model means nothing and
  // the usual cause is a too soft material or a too large time step. Each sphere has a limit and a
  // contact takes the smaller of its two spheres' (a wall has none):
  //  - the sphere of a one-sphere body: max_overlap_fraction of its radius;
  //  - a sphere of a clump: max_overlap_fraction of its body's volume-equivalent radius, and at
  //    most max_clump_sphere_overlap_fraction of its own radius. Such a sphere is a piece of the
  //    seed's surface, not a particle: the seed's own surface is curved on the scale of the seed
  //    (an ellipsoid's), and the small spheres of a fine fill are bumps that approximate it. Under
  //    a confining load (the 200 kPa shear box) such a bump takes an overlap of about its radius
  //    while the seed as a body deforms by about a tenth of its size. Past twice its radius the
  //    contact point, r - overlap / 2 from the sphere's centre, passes that centre and the
  //    contact's lever turns around: no geometry is left. Below that the run goes on and reports
  //    its deepest overlap (Simulation::deepest_overlap_fraction), how far the force law was
  //    carried beyond Hertz theory's range.
  double max_overlap_fraction = 0.5;
  double max_clump_sphere_overlap_fraction = 2.0;
  // Kinetic energy, less the potential energy released and the work the moving walls did, may not
  // exceed this multiple of the energy the scene can supply besides (initial kinetic energy, a
  // fall of one sphere diameter, every body at the fastest wall's speed; simulation.cpp).
  double max_energy_factor = 10.0;
  // Steps between energy checks (NaN is checked every step).
  int check_interval = 200;
};

enum class RunStatus { ok, non_finite, energy_runaway, deep_overlap, aborted };
const char* to_string(RunStatus s);

struct GuardFailure {
  RunStatus status = RunStatus::ok;
  std::uint64_t step = 0;
  double time_s = 0.0;
  std::int64_t body = -1;
  std::string message;
};

}  // namespace seedcal
