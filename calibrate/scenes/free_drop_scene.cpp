// `kind = "free_drop"`: schema in docs/scenes/free_drop.md.
#include "calibrate/config/particle_config.hpp"
#include "calibrate/config/physics_config.hpp"
#include "calibrate/scenes/scene_registry.hpp"
#include "solver/scenes/free_drop.hpp"

namespace seedcal {

nlohmann::json run_free_drop_scene(TomlReader& root, const SceneContext& ctx) {
  root.string("kind");
  root.choice("fidelity", {"paper", "quick"}, "paper");  // one body: both fidelities are the same
  PhysicsConfig phys = read_physics(root);
  FreeDropSpec spec;
  spec.physics = phys.physics;
  spec.time_step = phys.time_step;
  spec.threads = 1;
  spec.seed = ctx.seed;
  spec.observer = ctx.observer;
  const ParticleConfig particle = read_particle(root, phys, ctx.config_path, false);
  spec.body = particle.body;
  if (auto fd = root.table("free_drop")) {
    spec.drop_height_m = fd->number("drop_height_m", Range::left_open(0.0, 100.0), 0.150);
    spec.plate_material = phys.material(*fd, "plate_material", fd->string("plate_material"));
    phys.require_interaction(*fd, "plate_material", particle.material, spec.plate_material,
                             "the seed lands on the plate");
    spec.random_orientation = fd->boolean("random_orientation", true);
    spec.max_time_s = fd->number("max_time_s", Range::left_open(0.0, 1e3), 2.0);
    fd->check_unknown_keys();
  } else {
    root.error("free_drop", "is required: [free_drop] with plate_material (and drop_height_m)");
  }
  root.check_unknown_keys();
  root.diagnostics().throw_if_any();
  if (ctx.plan) *ctx.plan = plan_free_drop(spec);  // what the run will simulate (run_plan.hpp)
  if (ctx.check_only) {  // validated: run nothing
    return nlohmann::json::object();
  }

  const FreeDropResult r = run_free_drop(spec);
  nlohmann::json j;
  j["index_key"] = "rebound_height_m";
  j["rebound_height_m"] = r.rebound_height_m;
  j["contact_points"] = r.contact_points;
  j["impact_speed_m_s"] = r.impact_speed_m_s;
  j["rebound_speed_m_s"] = r.rebound_speed_m_s;
  j["restitution_com"] = r.impact_speed_m_s > 0 ? r.rebound_speed_m_s / r.impact_speed_m_s : 0.0;
  j["max_energy_ratio"] = r.max_energy_ratio;
  j["orientation_quat"] = {r.orientation.w(), r.orientation.x(), r.orientation.y(), r.orientation.z()};
  j["particle"] = particle.description;
  add_run_report(j, r.run);
  return j;
}

}  // namespace seedcal
