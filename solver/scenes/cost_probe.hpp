#pragma once
// This machine's CPU cost of one sphere-step of a bed of a given seed, measured before a study
// runs so that its plan (run_plan.hpp) can be priced in CPU seconds. Copies of the seed template
// are placed at random in a box, fall under a raised gravity into a bed, and the bed's next steps
// are timed on the run's CPU clock (scene_common.hpp, run_cpu_seconds). A bed at rest holds the
// most contacts per sphere any scene keeps for long (a pour, with fewer, is cheaper), so the cost
// prices the dense phases of a scene and overstates its pours.
#include <cstdint>

#include "solver/scenes/scene_common.hpp"
#include "solver/sim/body_def.hpp"

namespace seedcal {

struct CostProbe {
  double cpu_s_per_sphere_step = 0.0;
  std::size_t bodies = 0, spheres = 0;
  std::uint64_t timed_steps = 0;
  double probe_cpu_s = 0.0;  // the whole probe, falling included
};

// `physics` gives the materials and contact model (the seed's material is body.material), `dt_s`
// the scene's step. `bed` false: a scene of one or two bodies (a free drop, an impact), priced by
// one body alone in flight, whose material needs no interaction with itself. Deterministic in
// what it simulates; the cost is a clock reading.
CostProbe probe_sphere_step_cost(const PhysicsSpec& physics, const BodyDef& body, double dt_s, int threads,
                                 bool bed = true);

}  // namespace seedcal
