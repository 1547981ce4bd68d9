#include "calibrate/export/exported_model.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <numbers>

#include "calibrate/clumps/clump_source.hpp"
#include "calibrate/config/seed_config.hpp"
#include "calibrate/scenes/scene_file.hpp"
#include "solver/core/errors.hpp"
#include "store/errors.hpp"

namespace seedcal {

const Interaction* ExportedModel::interaction(std::uint16_t a, std::uint16_t b) const {
  for (const Interaction& i : physics.interactions)
    if ((i.material_a == a && i.material_b == b) || (i.material_a == b && i.material_b == a)) return &i;
  return nullptr;
}

double ExportedModel::volume_m3() const { return seeds.body.mass_kg / seed().density_kg_m3; }

// d = (6 V / pi)^(1/3), the sphere of the same volume.
double ExportedModel::volume_equivalent_diameter_m() const {
  return std::cbrt(6.0 * volume_m3() / std::numbers::pi);
}

double ExportedModel::bounding_radius_m() const {
  double r = 0.0;
  for (const SphereDef& s : seeds.body.spheres) r = std::max(r, s.offset_m.norm() + s.radius_m);
  return r;
}

double ExportedModel::largest_sphere_radius_m() const {
  double r = 0.0;
  for (const SphereDef& s : seeds.body.spheres) r = std::max(r, s.radius_m);
  return r;
}

double ExportedModel::smallest_sphere_radius_m() const {
  double r = seeds.body.spheres.empty() ? 0.0 : seeds.body.spheres.front().radius_m;
  for (const SphereDef& s : seeds.body.spheres) r = std::min(r, s.radius_m);
  return r;
}

ExportedModel exported_model_from_scene(const std::string& scene_path, const std::vector<std::string>& sets) {
  const SceneFile f = load_scene_file(scene_path, sets);
  auto diag = std::make_shared<ConfigDiagnostics>();
  diag->file = scene_path;
  TomlReader root(f.doc, "", diag);
  if (!root.has("particle"))
    throw InputError(scene_path + ": kind = \"" + f.kind +
                     "\": the scene has no [particle] seed to export (allowed: a seed scene, one with a [particle] "
                     "table: free_drop, bulk_density, direct_shear, piling, drum)");
  const SeedSceneConfig cfg = read_seed_scene(root, scene_path);
  diag->throw_if_any();
  ExportedModel m;
  m.scene_path = std::filesystem::path(scene_path).lexically_normal().string();
  m.physics = cfg.phys.physics;
  m.time_step = cfg.phys.time_step;
  m.seeds = cfg.seeds;
  m.seed_material = cfg.seed_material;
  m.particle_description = cfg.particle_description;
  if (!cfg.clump_file.empty())
    m.particle_description = std::filesystem::path(cfg.clump_file).lexically_normal().string();
  m.wall_material = m.seed_material;
  for (std::uint16_t k = 0; k < m.physics.materials.size(); ++k) {
    if (k != m.seed_material && m.interaction(m.seed_material, k)) {
      m.wall_material = k;
      break;
    }
  }
  return m;
}

double exported_time_step_s(const ExportedModel& m, double impact_speed_m_s) {
  SeedSpec one = m.seeds;
  one.scale = ScaleDistribution{};  // the template at scale 1, as exported
  try {
    return seed_time_step(m.physics, m.time_step, one, impact_speed_m_s);
  } catch (const SettingError& e) {
    throw InputError(m.scene_path + ": " + e.what());
  }
}

}  // namespace seedcal
