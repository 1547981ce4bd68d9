#pragma once
// Reads the parts every scene config shares (schema in docs/config.md):
//   gravity_m_s2 = [0, 0, -9.81]
//   dt_s, rayleigh_fraction, force_dt
//   [contact] model, rolling, rolling_lever, cdt_at_rest, clip_attractive, dashpot_velocity,
//             epsd_damping_ratio
//   [materials.NAME] density_kg_m3, youngs_modulus_pa, poisson_ratio
//   [[interaction]] name, between = [A, B], restitution, static_friction, rolling_friction
#include <map>
#include <string>

#include "calibrate/config/toml_reader.hpp"
#include "solver/scenes/scene_common.hpp"

namespace seedcal {

struct PhysicsConfig {
  PhysicsSpec physics;
  TimeStepSpec time_step;
  std::map<std::string, std::uint16_t> material_index;

  // Index of a material by name; records an error on `reader` (key `key`) when unknown.
  std::uint16_t material(TomlReader& reader, const std::string& key, const std::string& name) const;
};

PhysicsConfig read_physics(TomlReader& root);

}  // namespace seedcal
