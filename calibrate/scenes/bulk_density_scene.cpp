// `kind = "bulk_density"`: schema in docs/scenes/bulk_density.md.
#include "calibrate/scenes/rig_checks.hpp"
#include "calibrate/scenes/scene_schema.hpp"
#include "calibrate/scenes/seed_scene_common.hpp"
#include "solver/scenes/bulk_density.hpp"
#include "store/atomic_file.hpp"

namespace seedcal {

namespace {

// The scene's schema (scene_schema.hpp): its keys, their defaults (BulkDensitySpec's), its metrics.
SceneSchema<BulkDensitySpec> bulk_density_schema() {
  using S = BulkDensitySpec;
  SceneSchema<S> s("bulk_density", "`[bulk_density.paper]` / `[bulk_density.quick]`");
  s.vec3("container_m", &S::container_m, Range::closed(0.005, 10.0), true, "m", "inner size x, y, z")
      .material("wall_material", &S::wall_material, "the seeds touch the container", "the container's material")
      .number("collar_fraction", &S::collar_fraction, Range::closed(0.0, 5.0), "", "collar height / container height")
      .number("overfill", &S::overfill, Range::closed(0.5, 3.0), "", "poured mass / (volume x density x 0.62)")
      .number("settle_energy_ratio", &S::settle_energy_ratio, Range::open(0.0, 1.0), "",
              "settled below this kinetic energy per body / (m g d)")
      .number("max_time_s", &S::max_time_s, Range::left_open(0.0, 100.0), "s", "longest settling");
  s.metric("bulk_density_kg_m3", "kg/m3", "the index: mass of the seeds inside / container volume")
      .metric("solid_fraction", "", "bulk / particle density")
      .metric("seeds_inside", "", "seeds whose centre lies below the rim")
      .metric("seeds_poured", "", "seeds poured")
      .metric("mass_inside_kg", "kg", "mass of the seeds inside")
      .metric("container_m", "m", "the container's inner size x, y, z");
  return s;
}

}  // namespace

SchemaTable bulk_density_schema_table() { return bulk_density_schema().doc(); }

nlohmann::json run_bulk_density_scene(TomlReader& root, const SceneContext& ctx) {
  SeedSceneConfig cfg = read_seed_scene(root, ctx.config_path);
  BulkDensitySpec spec;
  fill_seed_spec(spec, cfg, ctx);
  const SceneSchema<BulkDensitySpec> schema = bulk_density_schema();
  if (auto rig = rig_table(root, "bulk_density", cfg.fidelity)) {
    schema.read(*rig, {cfg.phys, cfg.seed_material}, spec);
    warn_if_small_rig(*rig, "container_m", "the container's smallest side", spec.container_m.minCoeff(), spec.seeds,
                      kBulkContainer);
    rig->check_unknown_keys();
  }
  root.check_unknown_keys();
  root.diagnostics().throw_if_any();
  if (ctx.plan) *ctx.plan = plan_bulk_density(spec);  // what the run will simulate (run_plan.hpp)
  if (ctx.check_only) {  // validated: run nothing
    return nlohmann::json::object();
  }

  const BulkDensityResult r = run_bulk_density(spec);
  nlohmann::json j;
  j["index_key"] = "bulk_density_kg_m3";
  j["bulk_density_kg_m3"] = r.bulk_density_kg_m3;
  j["solid_fraction"] = r.solid_fraction;
  j["seeds_inside"] = r.seeds_inside;
  j["seeds_poured"] = r.seeds_poured;
  j["mass_inside_kg"] = r.mass_inside_kg;
  j["container_m"] = {spec.container_m.x(), spec.container_m.y(), spec.container_m.z()};
  add_seed_scene_keys(j, cfg, r.run);
  if (!ctx.out_dir.empty()) {
    // Raw data: every seed's centre and whether it counted; picture: side view with the rim.
    std::string csv = "x_m,y_m,z_m,inside\n";
    SideView view;
    view.title = "bulk density " + std::to_string(r.bulk_density_kg_m3) + " kg/m3 (rim in red)";
    for (std::size_t b = 0; b < r.centres.size(); ++b) {
      const auto& c = r.centres[b];
      csv += std::to_string(c.x()) + "," + std::to_string(c.y()) + "," + std::to_string(c.z()) + "," +
             (c.z() < spec.container_m.z() ? "1" : "0") + "\n";
      for (const auto& [p, rad] : r.spheres[b]) view.circles.push_back({project(p, Eigen::Vector3d::UnitX()), rad});
    }
    view.lines.push_back({0.0, spec.container_m.z(), spec.container_m.x(), spec.container_m.z(), "#d62728", "rim"});
    write_file_atomic(ctx.out_dir + "/bulk_density_seeds.csv", csv);
    write_file_atomic(ctx.out_dir + "/bulk_density.svg", render_svg(view));
  }
  schema.check_metrics(j);
  return j;
}

}  // namespace seedcal
