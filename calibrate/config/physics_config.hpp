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

  // What material() returns for an unknown name (the error is recorded).
  static constexpr std::uint16_t kUnknown = 0xFFFF;

  // Index of a material by name; records an error on `reader` (key `key`) and returns kUnknown
  // when unknown.
  std::uint16_t material(TomlReader& reader, const std::string& key, const std::string& name) const;

  // Records an error on `reader` (key `key`, the setting that brings material `b` into the scene)
  // when materials a and b, which touch in the scene (`how`, e.g. "the seeds touch the plate"),
  // have no [[interaction]]: such a pair would pass through each other with zero force. Unknown
  // materials (already reported) are skipped.
  void require_interaction(TomlReader& reader, const std::string& key, std::uint16_t a, std::uint16_t b,
                           const std::string& how) const;
};

PhysicsConfig read_physics(TomlReader& root);

}  // namespace seedcal
