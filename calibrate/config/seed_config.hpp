#pragma once
// What the seed scenes share in their configs: the fidelity, the [particle] table with its scale
// distribution, and the rig table of the chosen fidelity:
//   fidelity = "paper" | "quick"
//   variety = "../../varieties/NAME.toml"    # the seed's values (calibrate/config/variety_scene.hpp)
//   [particle] material, clump_file | spheres_m | model,
//              scale_sd = 0.13, scale_min = 0.74, scale_max = 1.26   # optional; mean is 1
//   [RIG.paper] ... / [RIG.quick] ...                                 # per-fidelity rig keys
#include <optional>
#include <string>

#include "calibrate/config/particle_config.hpp"
#include "solver/scenes/seed_bed.hpp"

namespace seedcal {

struct SeedSceneConfig {
  PhysicsConfig phys;
  SeedSpec seeds;
  std::string fidelity;
  std::string particle_description;
  std::string clump_file;  // the clump file the seeds come from (resolved); "" for inline spheres
  std::uint16_t seed_material = PhysicsConfig::kUnknown;

  // Records an error on `rig` (key `key`) when the seeds and `wall_material` have no interaction.
  void require_wall_interaction(TomlReader& rig, const std::string& key, std::uint16_t wall_material,
                                const std::string& how) const {
    phys.require_interaction(rig, key, seed_material, wall_material, how);
  }
};

SeedSceneConfig read_seed_scene(TomlReader& root, const std::string& config_path);

// The rig table for the chosen fidelity: [rig.<fidelity>] inside [rig] (other fidelities' tables
// are marked read so they are not reported as unknown, but are not validated here).
std::optional<TomlReader> rig_table(TomlReader& root, const std::string& rig, const std::string& fidelity);

}  // namespace seedcal
