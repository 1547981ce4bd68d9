// `kind = "piling"`: schema in docs/scenes/piling.md.
#include <numbers>
#include <sstream>

#include "calibrate/scenes/rig_checks.hpp"
#include "calibrate/scenes/scene_schema.hpp"
#include "calibrate/scenes/seed_scene_common.hpp"
#include "solver/scenes/piling.hpp"
#include "store/atomic_file.hpp"

namespace seedcal {

namespace {

// The scene's schema (scene_schema.hpp): its keys, their defaults (PilingSpec's), its metrics.
SceneSchema<PilingSpec> piling_schema() {
  SceneSchema<PilingSpec> s("piling", "`[piling.paper]` / `[piling.quick]`");
  s.material("plate_material", &PilingSpec::plate_material, "the seeds pile on the plate", "the plate's material")
      .material("tube_material", &PilingSpec::tube_material, "the seeds fill the tube", "the tube's material")
      .number("tube_diameter_m", &PilingSpec::tube_diameter_m, Range::closed(0.005, 5.0), "m", "tube inner diameter")
      .number("fill_height_m", &PilingSpec::fill_height_m, Range::closed(0.005, 5.0), "m",
              "fill height (sets the seed mass)")
      .number("lift_speed_m_s", &PilingSpec::lift_speed_m_s, Range::closed(1e-5, 10.0), "m/s", "tube speed")
      .integer("azimuths", &PilingSpec::azimuths, 2, 72, "sectors the heap is cut into")
      .number("fit_window_min", &PilingSpec::window_lo, Range::closed(0.0, 0.9), "",
              "lower end of the fit window, a fraction of the sector's height; below `fit_window_max`")
      .number("fit_window_max", &PilingSpec::window_hi, Range::closed(0.1, 1.0), "",
              "upper end of the fit window, a fraction of the sector's height")
      .number("max_time_s", &PilingSpec::max_time_s, Range::left_open(0.0, 100.0), "s", "longest final settling");
  s.metric("angle_of_repose_deg", "deg", "the index: mean of the sectors' angles")
      .metric("angle_of_repose_sectors_sd_deg", "deg", "sd of the sectors' angles")
      .metric("sector_angles_deg", "deg", "every sector's angle")
      .metric("heap_radius_m", "m", "radius holding 95 % of the seed centres")
      .metric("heap_height_m", "m", "highest sphere top")
      .metric("heap_foot_radius_m", "m", "mean foot radius over the sectors")
      .metric("tube_lift_m", "m", "how far the tube was lifted")
      .metric("seeds", "", "seeds in the scene");
  return s;
}

}  // namespace

SchemaTable piling_schema_table() { return piling_schema().doc(); }

nlohmann::json run_piling_scene(TomlReader& root, const SceneContext& ctx) {
  SeedSceneConfig cfg = read_seed_scene(root, ctx.config_path);
  PilingSpec spec;
  fill_seed_spec(spec, cfg, ctx);
  const SceneSchema<PilingSpec> schema = piling_schema();
  if (auto rig = rig_table(root, "piling", cfg.fidelity)) {
    schema.read(*rig, {cfg.phys, cfg.seed_material}, spec);
    warn_if_small_rig(*rig, "tube_diameter_m", "the tube's diameter", spec.tube_diameter_m, spec.seeds, kPilingTube);
    if (spec.window_lo >= spec.window_hi) rig->error("fit_window_min", "must be below fit_window_max");
    rig->check_unknown_keys();
  }
  root.check_unknown_keys();
  root.diagnostics().throw_if_any();
  if (ctx.plan) *ctx.plan = plan_piling(spec);  // what the run will simulate (run_plan.hpp)
  if (ctx.check_only) {  // validated: run nothing
    return nlohmann::json::object();
  }

  const PilingResult r = run_piling(spec);
  nlohmann::json j;
  j["index_key"] = "angle_of_repose_deg";
  j["angle_of_repose_deg"] = r.angle_of_repose_deg;
  j["angle_of_repose_sectors_sd_deg"] = r.angle_sd_deg;
  j["sector_angles_deg"] = r.sector_angles_deg;
  j["heap_radius_m"] = r.heap_radius_m;
  j["heap_height_m"] = r.heap_height_m;
  j["heap_foot_radius_m"] = r.foot_radius_m;
  j["tube_lift_m"] = r.lift_m;
  j["seeds"] = r.seeds;
  add_seed_scene_keys(j, cfg, r.run);
  if (!ctx.out_dir.empty()) {
    std::ostringstream csv;
    csv << "sector,azimuth_deg,r_m,z_m\n";
    for (std::size_t a = 0; a < r.profiles.size(); ++a)
      for (const auto& [rr, z] : r.profiles[a])
        csv << a << "," << 360.0 * static_cast<double>(a) / static_cast<double>(r.profiles.size()) << "," << rr << "," << z << "\n";
    write_file_atomic(ctx.out_dir + "/piling_profile.csv", csv.str());
    // Side view along x with the fits of the two opposite sectors 0 and n/2 (both sides).
    SideView view;
    view.title = "angle of repose " + std::to_string(r.angle_of_repose_deg) + " deg";
    add_spheres(view, r.spheres);
    const std::size_t half = r.fits.size() / 2;
    for (std::size_t a : {std::size_t{0}, half}) {
      if (a >= r.fits.size() || !r.fits[a].ok) continue;
      const double sign = a == 0 ? 1.0 : -1.0;
      const double r0 = r.fit_ranges[a].first, r1 = r.fit_ranges[a].second;
      view.lines.push_back({sign * r0, r.fits[a].intercept + r.fits[a].slope * r0, sign * r1,
                            r.fits[a].intercept + r.fits[a].slope * r1, "#d62728", ""});
    }
    write_file_atomic(ctx.out_dir + "/piling.svg", render_svg(view));
  }
  schema.check_metrics(j);
  return j;
}

}  // namespace seedcal
