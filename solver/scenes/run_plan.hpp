#pragma once
// What a scene run will simulate, worked out from its spec before anything runs: the time step,
// the seeds and spheres it holds, and the simulated time of each phase of its protocol. A phase of
// fixed length (a shear path at its speed, a drum's frame times, a lift at its speed) is exact; a
// phase that ends on a criterion (a pour in batches, settling, consolidation) is an estimate from
// the rig's geometry (run_plan.cpp says how). `seedcal calibrate --dry-run` turns plans into CPU
// time with this machine's measured cost of a sphere-step (cost_probe.hpp); `seedcal run` shows the
// simulated time against the plan's.
#include <string>
#include <vector>

#include "solver/scenes/seed_bed.hpp"

namespace seedcal {

struct PlanPhase {
  std::string name;          // "pour", "settle", "shear", ...
  double simulated_s = 0.0;  // simulated time of the phase
  double spheres = 0.0;      // mean number of spheres in the world during the phase
  bool estimated = false;    // ends on a criterion: simulated_s is an estimate
  // The stress a servo holds on the bed during the phase (the shear box's consolidation and shear),
  // Pa; 0 when none. Under it each surface sphere of a fine clump holds several contacts, so the
  // cost probe prices such a phase on a bed loaded to it.
  double confining_stress_pa = 0.0;
};

struct RunPlan {
  double dt_s = 0.0;
  double seeds = 0.0;    // bodies at the end of the pour (the most the run holds)
  double spheres = 0.0;  // their spheres
  BodyDef body;          // the seed template (the cost probe packs copies of it)
  PhysicsSpec physics;   // its materials and contact model
  std::vector<PlanPhase> phases;

  double simulated_s() const;
  double steps() const;         // simulated_s / dt_s
  double sphere_steps() const;  // sum over the phases of spheres x simulated_s / dt_s
};

// Mean number of seeds in `mass_kg` (the template's mass x E[s^3] per seed, as seed_volume_m3).
double seeds_in_mass(const SeedSpec& seeds, double mass_kg);

// Estimated simulated time of a pour of `mass_kg` into an insertion region of `region_m3`, in at
// most `batches` batches `interval_s` apart: the factory places random non-overlapping poses, which
// jam for elongated seeds at about a quarter of the region's volume (random sequential addition
// reaches 0.38 for spheres and less for elongated bodies: Sherwood, J. Phys. A 30 (1997) L839), so
// each batch holds about a quarter of the region's volume of seed material.
double pour_time_s(double mass_kg, double density_kg_m3, double region_m3, int batches, double interval_s);

// Estimated time for seeds dropped from `height_m` to settle, capped at `max_time_s`: their fall
// time sqrt(2 h / g) and a tenth of a second for the bed's collisions to die out (a bed of seeds
// with e ~ 0.5 loses 3/4 of its energy at every collision, milliseconds apart).
double settle_time_s(double height_m, double gravity_m_s2, double max_time_s);

}  // namespace seedcal
