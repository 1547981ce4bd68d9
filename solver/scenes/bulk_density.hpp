#pragma once
// The `bulk_density` scene: seeds poured into a container of known volume, settled, the excess
// struck off at the rim, bulk density = mass inside / container volume.
//
// Protocol (documented in docs/scenes/bulk_density.md): an open box of inner size L x W x H with a
// collar of `collar_fraction` x H above the rim (so the excess stays above the container as it
// does under the lab's funnel), seeds inserted by the factory in the collar and above it until the
// poured mass reaches `overfill` x (container volume x particle density x 0.62; 0.62 is above the
// solid fraction of any random seed packing, ~0.5, so overfill 1 leaves ~25 % excess), settled to a
// kinetic-energy threshold, then struck off: a seed counts as inside when its centre of mass is
// below the rim plane (by centroid; the by-volume alternative differs by a fraction of a seed layer).
#include "solver/scenes/run_plan.hpp"

namespace seedcal {

struct BulkDensitySpec {
  PhysicsSpec physics;
  TimeStepSpec time_step;
  SeedSpec seeds;
  std::uint16_t wall_material = 0;
  Vec3 container_m = Vec3(0.1, 0.1, 0.1);
  double collar_fraction = 0.6;
  double overfill = 1.0;
  double settle_energy_ratio = 1e-4;
  double max_time_s = 3.0;
  int threads = 1;
  std::uint64_t seed = 0;
  FrameObserver observer;  // frames for a trajectory (optional)
};

struct BulkDensityResult {
  RunReport run;
  double bulk_density_kg_m3 = 0.0;
  double solid_fraction = 0.0;
  std::size_t seeds_inside = 0, seeds_poured = 0;
  double mass_inside_kg = 0.0;
  std::vector<Vec3> centres;  // of all seeds, for the picture
  std::vector<double> radii;  // bounding radius per seed (picture)
  std::vector<std::vector<std::pair<Vec3, double>>> spheres;  // per seed, world spheres (picture)
};

BulkDensityResult run_bulk_density(const BulkDensitySpec& spec);
// What a run of `spec` will simulate (run_plan.hpp).
RunPlan plan_bulk_density(const BulkDensitySpec& spec);

}  // namespace seedcal
