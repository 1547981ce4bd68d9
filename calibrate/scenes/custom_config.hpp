#pragma once
// Reads a `kind = "custom"` scene's rig (schema: docs/scenes/custom.md) into a CustomSpec:
//   [[custom.wall]]    the walls: shape, material, placement, optional motion law
//   [custom.fill]      the factory's box and options
//   [[custom.measure]] the measurements
//   sink_z_m           optional, in [custom]
//   [custom.paper] / [custom.quick]   what the fidelity sets: the fill's mass or count, settling,
//                                     the run's time, the sampling
// Every problem is recorded on the readers (file, key, value, allowed range); the caller throws.
#include <string>

#include "calibrate/config/seed_config.hpp"
#include "solver/scenes/custom_rig.hpp"

namespace seedcal {

CustomSpec read_custom_rig(TomlReader& root, const SeedSceneConfig& cfg, const std::string& config_path);

}  // namespace seedcal
