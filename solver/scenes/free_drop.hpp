#pragma once
// The `free_drop` scene: one clump released at rest from a height onto a plate (the paper's
// individual-particle test, 150 mm onto steel). It measures the rebound height of the centre of
// mass and the number of sphere-level contact points during the first impact, and stops at the
// apex of the first rebound.
#include "solver/scenes/run_plan.hpp"
#include "solver/sim/body_def.hpp"

namespace seedcal {

struct FreeDropSpec {
  PhysicsSpec physics;
  TimeStepSpec time_step;
  BodyDef body;                   // spheres in the principal frame, mass properties
  std::uint16_t plate_material = 0;
  double drop_height_m = 0.150;   // gap between the clump's lowest point and the plate
  bool random_orientation = true; // uniform random orientation from the seed (else body.orientation)
  double max_time_s = 2.0;
  int threads = 1;
  std::uint64_t seed = 0;
  FrameObserver observer;  // frames for a trajectory (optional)
};

struct FreeDropResult {
  RunReport run;
  double rebound_height_m = 0.0;   // apex of the centre of mass after the first impact, above its
                                   // height at first touch
  int contact_points = 0;          // most sphere-level contacts at once during the first impact
  double impact_speed_m_s = 0.0;   // centre-of-mass vertical speed at the end of the last step
                                   // before the first touch
  double rebound_speed_m_s = 0.0;  // centre-of-mass vertical speed leaving the plate
  // Largest kinetic plus potential energy (above the centre's height at first touch) over the
  // run, divided by the energy at release m g drop_height_m. The elastic energy stored in the
  // contact is not counted, so a correct run stays at or below 1; above 1 the integrator gained
  // energy (a time step too large for the contact).
  double max_energy_ratio = 0.0;
  Quat orientation = Quat::Identity();
};

FreeDropResult run_free_drop(const FreeDropSpec& spec);
// What a run of `spec` will simulate (run_plan.hpp).
RunPlan plan_free_drop(const FreeDropSpec& spec);

}  // namespace seedcal

