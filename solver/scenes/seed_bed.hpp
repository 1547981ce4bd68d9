#pragma once
// Shared by the seed scenes: the time step for a particle template and its scale range, and the
// insertion of seeds by the particle factory.
#include <chrono>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "solver/scenes/scene_common.hpp"
#include "solver/sim/particle_factory.hpp"

namespace seedcal {

// Seeds of a scene: a template body, its scale distribution and material.
struct SeedSpec {
  BodyDef body;
  ScaleDistribution scale;  // mean 1 = the template's size
};

// dt for a scene whose smallest sphere is the template's smallest scaled by scale.lo, at the
// expected impact speed (e.g. free fall from the insertion height).
double seed_time_step(const PhysicsSpec& physics, const TimeStepSpec& ts, const SeedSpec& seeds,
                      double impact_speed_m_s);

// Refuses, before anything is allocated, a pour of `mass_kg` of seeds that would not fit in the
// memory available (sim/memory_estimate.hpp): throws SettingError naming `key`, with `rig` (the
// rig's size in words) and the estimate in the message.
void check_pour_memory(const PhysicsSpec& physics, const SeedSpec& seeds, double mass_kg, int threads,
                       const std::string& key, const std::string& rig);

// "diameter_m = 0.2, depth_m = 0.05": a rig's size for messages.
std::string describe_rig(std::initializer_list<std::pair<const char*, double>> keys);

// Simulation options common to the seed scenes; `observer` takes the run's frames (optional).
SimulationOptions seed_options(const PhysicsSpec& physics, double dt_s, int threads, std::uint64_t seed,
                               const FrameObserver& observer = {});

// Pours seeds with the factory in up to `batches` batches until `mass_kg` is placed, letting each
// batch fall for `fall_s` to make room for the next. Returns the mass placed.
double pour_seeds(Simulation& sim, const FactorySpec& spec, double mass_kg, int batches, double fall_s);

// The highest point of any sphere (centre z + radius), m; 0 (the floor) with none above it.
double highest_point_m(const Simulation& sim);

// World spheres of every body (for pictures).
std::vector<std::vector<std::pair<Vec3, double>>> body_spheres(const Simulation& sim);

// Opens the protocol phase `name` of a run at the simulation's current time (closing the phase
// before it): PhaseRecord. end_phase() closes the open one now (finish_report() does).
void begin_phase(RunReport& r, const Simulation& sim, const std::string& name);
void end_phase(RunReport& r, const Simulation& sim);

// Fills the counters and timings of a scene's run report, closing its last phase.
// Runs the simulation's final guard check first (a failure there is reported like any other).
void finish_report(RunReport& r, Simulation& sim, double cpu0_s,
                   std::chrono::steady_clock::time_point wall_t0);

// Mean volume of one seed (template volume x E[s^3]), m3, from the template's mass and density.
double seed_volume_m3(const SeedSpec& seeds, double density_kg_m3);

}  // namespace seedcal
