#pragma once
// This machine's CPU cost of one sphere-step of a bed of a given seed, measured before a study
// runs so that its plan (run_plan.hpp) can be priced in CPU seconds. Copies of the seed template
// are placed at random in a box, fall under a raised gravity into a bed, and the bed's next steps
// are timed on the run's CPU clock (scene_common.hpp, run_cpu_seconds). A bed at rest holds the
// most contacts per sphere an unloaded scene keeps for long (a pour, with fewer, is cheaper), so
// the cost prices the dense phases of a scene and overstates its pours; a phase a servo loads
// (RunPlan's confining_stress_pa) is priced on a bed pressed to that stress.
#include <cstdint>

#include "solver/scenes/scene_common.hpp"
#include "solver/sim/body_def.hpp"

namespace seedcal {

struct CostProbe {
  double cpu_s_per_sphere_step = 0.0;
  std::size_t bodies = 0, spheres = 0;
  std::uint64_t timed_steps = 0;
  double probe_cpu_s = 0.0;  // the whole probe, falling included
  // A loaded probe: the stress asked for, and the mean stress the lid held over the timed steps.
  double confining_stress_pa = 0.0, measured_stress_pa = 0.0;
};

// `physics` gives the materials and contact model (the seed's material is body.material), `dt_s`
// the scene's step. `bed` false: a scene of one or two bodies (a free drop, an impact), priced by
// one body alone in flight, whose material needs no interaction with itself. Deterministic in
// what it simulates; the cost is a clock reading. `confining_stress_pa` > 0 (a bed only): a servo
// lid presses the bed at that stress before the timed steps (a bed at least two seeds deep), as the
// shear box's cap does: the cost of a sphere-step under load.
CostProbe probe_sphere_step_cost(const PhysicsSpec& physics, const BodyDef& body, double dt_s, int threads,
                                 bool bed = true, double confining_stress_pa = 0.0);

}  // namespace seedcal
