#include "calibrate/config/seed_config.hpp"

namespace seedcal {

SeedSceneConfig read_seed_scene(TomlReader& root, const std::string& config_path) {
  SeedSceneConfig c;
  root.string("kind");
  c.fidelity = root.choice("fidelity", {"paper", "quick"}, "paper");
  c.phys = read_physics(root);
  const ParticleConfig particle = read_particle(root, c.phys, config_path, true);
  c.seeds.body = particle.body;
  c.seeds.scale = particle.scale;
  c.particle_description = particle.description;
  c.clump_file = particle.clump_file;
  c.seed_material = particle.material;
  return c;
}

std::optional<TomlReader> rig_table(TomlReader& root, const std::string& rig, const std::string& fidelity) {
  auto t = root.table(rig);
  if (!t) {
    root.error(rig, "is required: a [" + rig + "." + fidelity + "] table with the rig");
    return std::nullopt;
  }
  for (const std::string& f : {std::string("paper"), std::string("quick")})
    if (f != fidelity) t->table(f);  // mark read
  auto chosen = t->table(fidelity);
  t->check_unknown_keys();
  if (!chosen) t->error(fidelity, "is required: the rig for fidelity \"" + fidelity + "\"");
  return chosen;
}

}  // namespace seedcal
