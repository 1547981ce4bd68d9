#pragma once
// Shared by the seed scenes: the time step for a particle template and its scale range, and the
// insertion of seeds by the particle factory.
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

// Simulation options common to the seed scenes.
SimulationOptions seed_options(const PhysicsSpec& physics, double dt_s, int threads, std::uint64_t seed);

// Mean volume of one seed (template volume x E[s^3]), m3, from the template's mass and density.
double seed_volume_m3(const SeedSpec& seeds, double density_kg_m3);

}  // namespace seedcal
