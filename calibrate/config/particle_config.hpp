#pragma once
// The particle a seed scene uses, from the [particle] table:
//   [particle]
//   material = "seed"                                   # a [materials.NAME]
//   clump_file = "data/clumps/jinong1-manual-9.toml"    # a clump file (seedcal clump build), or
//   spheres_m = [[x, y, z, r], ...]                     # spheres inline (any frame), or
//   model = "manual-9"                                  # one of the variety's [models]
// With a top-level `variety` and none of the three, the variety's default_model
// (calibrate/config/variety_scene.hpp).
//   scale_sd = 0.13, scale_min = 0.74, scale_max = 1.26 # optional size distribution (mean 1)
// Mass properties come from the union of the spheres and the material's density.
#include <string>

#include "calibrate/config/physics_config.hpp"
#include "solver/sim/body_def.hpp"
#include "solver/sim/particle_factory.hpp"

namespace seedcal {

struct ParticleConfig {
  BodyDef body;              // principal frame, mass properties set, material set
  std::uint16_t material = PhysicsConfig::kUnknown;  // the seeds' material
  std::string description;   // e.g. the clump file name, for reports
  std::string clump_file;    // the clump file read (resolved); "" for inline spheres
  ScaleDistribution scale;   // truncated normal, mean 1 (the template's size)
};

// many_seeds: the scene holds more than one seed, so the seed material's pair with itself needs an
// [[interaction]] (recorded as an error on [particle] material when it has none).
ParticleConfig read_particle(TomlReader& root, const PhysicsConfig& phys, const std::string& config_path,
                             bool many_seeds);

}  // namespace seedcal
