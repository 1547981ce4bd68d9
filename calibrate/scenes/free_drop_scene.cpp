// `kind = "free_drop"`: schema in docs/scenes/free_drop.md.
#include "calibrate/config/particle_config.hpp"
#include "calibrate/config/physics_config.hpp"
#include "calibrate/scenes/scene_registry.hpp"
#include "calibrate/scenes/scene_schema.hpp"
#include "solver/scenes/free_drop.hpp"

namespace seedcal {

namespace {

// The scene's schema (scene_schema.hpp): its keys, their defaults (FreeDropSpec's), its metrics.
SceneSchema<FreeDropSpec> free_drop_schema() {
  using S = FreeDropSpec;
  SceneSchema<S> s("free_drop", "`[free_drop]` (one body: both fidelities are the same scene)");
  s.number("drop_height_m", &S::drop_height_m, Range::left_open(0.0, 100.0), "m",
           "gap between the clump's lowest point and the plate at release")
      .material("plate_material", &S::plate_material, "the seed lands on the plate", "the plate's material")
      .flag("random_orientation", &S::random_orientation,
            "a uniformly random orientation drawn from the run's seed (else the clump file's)")
      .number("max_time_s", &S::max_time_s, Range::left_open(0.0, 1e3), "s", "longest run");
  s.metric("rebound_height_m", "m", "the index: rise of the centre of mass above its height at touch-down")
      .metric("contact_points", "", "the second index: most sphere-plate contacts at once during the impact")
      .metric("impact_speed_m_s", "m/s", "speed of the centre of mass at the first touch")
      .metric("rebound_speed_m_s", "m/s", "its speed when the clump leaves the plate")
      .metric("restitution_com", "", "rebound speed / impact speed")
      .metric("max_energy_ratio", "",
              "largest total energy over the release energy (above 1 would mean the integrator made energy)")
      .metric("orientation_quat", "", "the clump's orientation at release (w, x, y, z)");
  return s;
}

}  // namespace

SchemaTable free_drop_schema_table() { return free_drop_schema().doc(); }

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
  const SceneSchema<FreeDropSpec> schema = free_drop_schema();
  if (auto fd = root.table("free_drop")) {
    schema.read(*fd, {phys, particle.material}, spec);
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
  schema.check_metrics(j);
  return j;
}

}  // namespace seedcal
