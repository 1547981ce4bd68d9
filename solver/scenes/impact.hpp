#pragma once
// The `impact` scene: one or more bodies with given positions, velocities and spins, optional plane
// walls, run for a fixed duration. It measures the first impact (first touch to last separation),
// the peak overlap and force, the most sphere-level contact points of one body, and the final
// state of every body. Used for validation against contact mechanics.
#include <functional>
#include <memory>
#include <vector>

#include "solver/scenes/run_plan.hpp"
#include "solver/sim/body_def.hpp"

namespace seedcal {

struct ImpactWallSpec {
  Vec3 point_m = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();
  std::uint16_t material = 0;
};

struct ImpactSpec {
  PhysicsSpec physics;
  TimeStepSpec time_step;
  double duration_s = 0.0;
  std::vector<BodyDef> bodies;  // mass properties filled in
  std::vector<ImpactWallSpec> walls;
  int threads = 1;
  std::uint64_t seed = 0;
  FrameObserver observer;  // frames for a trajectory (optional)
};

struct BodyFinalState {
  Vec3 position_m, velocity_m_s, angular_velocity_rad_s;
};

struct ImpactResult {
  RunReport run;
  double contact_duration_s = 0.0;  // first impact: first touch to last separation
  double first_touch_s = -1.0;
  double max_overlap_m = 0.0;
  double max_normal_force_n = 0.0;
  int max_contact_points = 0;
  std::vector<BodyFinalState> final_states;
};

// Optional per-step observer (tests use it to record histories).
using StepObserver = std::function<void(const Simulation&)>;

ImpactResult run_impact(const ImpactSpec& spec, const StepObserver& observer = {});
// What a run of `spec` will simulate (run_plan.hpp).
RunPlan plan_impact(const ImpactSpec& spec);

}  // namespace seedcal
