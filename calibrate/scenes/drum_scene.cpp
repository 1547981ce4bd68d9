// `kind = "drum"`: schema in docs/scenes/drum.md.
#include <sstream>

#include "calibrate/scenes/rig_checks.hpp"
#include "calibrate/scenes/scene_schema.hpp"
#include "calibrate/scenes/seed_scene_common.hpp"
#include "solver/scenes/drum.hpp"
#include "store/atomic_file.hpp"

namespace seedcal {

namespace {

// The scene's schema (scene_schema.hpp): its keys, their defaults (DrumSpec's), its metrics.
SceneSchema<DrumSpec> drum_schema() {
  using S = DrumSpec;
  SceneSchema<S> s("drum", "`[drum.paper]` / `[drum.quick]`");
  s.material("drum_material", &S::drum_material, "the seeds touch the drum", "the shell's and end faces' material")
      .number("diameter_m", &S::diameter_m, Range::closed(0.01, 10.0), "m", "inner diameter")
      .number("depth_m", &S::depth_m, Range::closed(0.005, 10.0), "m", "inner depth (between the end faces)")
      .number("filling_rate", &S::filling_rate, Range::open(0.0, 0.9), "", "bed volume / drum volume")
      .number("bulk_density_kg_m3", &S::bulk_density_kg_m3, Range::closed(1.0, 2e4), "kg/m3",
              "bulk density used to turn the fill into a seed mass")
      .default_is("the variety's `[targets] bulk_density_kg_m3` (680 without a variety)")
      .number("speed_rpm", &S::speed_rpm, Range::closed(0.01, 1000.0), "rpm", "rotation speed (one run is one speed)")
      .numbers("frame_times_s", &S::frame_times_s, Range::closed(0.0, 1000.0), 1, 100, "s",
               "frame times after the drum starts turning")
      .number("fit_width_fraction", &S::fit_width_fraction, Range::left_open(0.0, 1.0), "",
              "central part of the chord that is fitted")
      .integer("shell_facets", &S::shell_facets, 0, 720,
               "0: a smooth circular shell; N (3 or more): a shell of N flat facets inscribed in the circle (a "
               "drum made of plates, or a CAD drum imported as a triangle mesh), whose edges grip the seeds; the "
               "end faces stay flat discs");
  s.metric("dynamic_angle_of_repose_deg", "deg", "the index: mean of the frames' surface angles")
      .metric("dynamic_angle_frames_sd_deg", "deg", "sd of the frames' angles")
      .metric("dynamic_angle_frames_measured", "", "frames whose surface line was fitted")
      .metric("dynamic_angle_frames_failed", "", "frames with too few surface points in the fit band")
      .metric("frames", "", "every frame: time_s, fit_ok, angle_deg, r2, wall_layer_speed_ratio")
      .metric("wall_layer_speed_ratio", "",
              "mean over the frames of the mass-weighted speed along the turn of the seeds within one seed length "
              "of the shell, over the shell's speed: about 1 when the wall carries the bed up, about 0 when the "
              "shell slides under a bed at rest")
      .metric("slipping_frames", "", "frames whose wall layer moves at less than 0.1 of the shell's speed")
      .metric("speed_rpm", "rpm", "the drum's speed")
      .metric("shell_facets", "", "the shell's facets (0: smooth)")
      .metric("froude_number", "", "w^2 R / g")
      .metric("fill_height_m", "m", "the bed's depth at the drum's centre line")
      .metric("seeds", "", "seeds in the drum");
  return s;
}

// The name of material `index` in the config (for the warnings).
std::string material_name(const PhysicsConfig& phys, std::uint16_t index) {
  for (const auto& [name, i] : phys.material_index)
    if (i == index) return name;
  return "the drum's material";
}

}  // namespace

SchemaTable drum_schema_table() { return drum_schema().doc(); }

nlohmann::json run_drum_scene(TomlReader& root, const SceneContext& ctx) {
  SeedSceneConfig cfg = read_seed_scene(root, ctx.config_path);
  DrumSpec spec;
  fill_seed_spec(spec, cfg, ctx);
  const SceneSchema<DrumSpec> schema = drum_schema();
  if (auto rig = rig_table(root, "drum", cfg.fidelity)) {
    schema.read(*rig, {cfg.phys, cfg.seed_material}, spec);
    if (spec.shell_facets == 1 || spec.shell_facets == 2)
      rig->error("shell_facets", "is " + std::to_string(spec.shell_facets) +
                                     "; allowed: 0 (a smooth shell) or 3 to 720 facets");
    warn_if_small_rig(*rig, "filling_rate", "the bed's depth at the drum's centre line",
                      drum_fill_height(0.5 * spec.diameter_m, spec.filling_rate), spec.seeds, kDrumBed,
                      "raise the filling rate or the drum's diameter");
    warn_if_small_rig(*rig, "depth_m", "the drum's depth", spec.depth_m, spec.seeds, kDrumDepth);
    rig->check_unknown_keys();
  }
  root.check_unknown_keys();
  root.diagnostics().throw_if_any();
  if (ctx.plan) *ctx.plan = plan_drum(spec);  // what the run will simulate (run_plan.hpp)
  if (ctx.check_only) {  // validated: run nothing
    return nlohmann::json::object();
  }

  const DrumResult r = run_drum(spec);
  nlohmann::json j;
  j["index_key"] = "dynamic_angle_of_repose_deg";
  j["dynamic_angle_of_repose_deg"] = r.dynamic_angle_of_repose_deg;
  j["dynamic_angle_frames_sd_deg"] = r.angle_sd_deg;
  j["dynamic_angle_frames_measured"] = r.measured_frames;
  j["dynamic_angle_frames_failed"] = r.failed_frames;
  nlohmann::json frames = nlohmann::json::array();
  for (const DrumFrame& f : r.frames)
    frames.push_back({{"time_s", f.time_s}, {"fit_ok", f.fit.ok}, {"angle_deg", f.angle_deg}, {"r2", f.fit.r2},
                      {"wall_layer_speed_ratio", f.wall_layer_speed_ratio}});
  j["frames"] = frames;
  j["wall_layer_speed_ratio"] = r.wall_layer_speed_ratio;
  j["slipping_frames"] = r.slipping_frames;
  if (r.slipping_frames > 0) {
    // Said beside the index: such a frame's angle is the bed's angle of failure on the shell, which
    // no speed changes (docs/scenes/drum.md; measured in docs/results/drum.md).
    std::ostringstream w;
    w << "the bed slipped on the shell in " << r.slipping_frames << " of " << r.frames.size()
      << " frames (wall layer below 0.1 of the shell's speed): those angles are held by the "
         "shell's friction, not by the bed's flow, and do not change with the speed; a shell with "
         "more grip (the drum's lining: a higher static_friction between the seeds and "
      << material_name(cfg.phys, spec.drum_material) << ") carries the bed";
    j["warnings"].push_back(w.str());
  }
  if (r.failed_frames > 0) {
    std::ostringstream w;
    w << "the surface line fit failed in " << r.failed_frames << " of " << r.frames.size()
      << " frames (fewer than 3 surface points in the fit band): the dynamic angle and its sd are over the "
      << r.measured_frames << " measured frames"
      << (r.measured_frames == 0 ? ", so there is none: widen fit_width_fraction or fill the drum more" : "");
    j["warnings"].push_back(w.str());
  }
  j["speed_rpm"] = spec.speed_rpm;
  j["shell_facets"] = spec.shell_facets;
  j["froude_number"] = r.froude_number;
  j["fill_height_m"] = r.fill_height_m;
  j["seeds"] = r.seeds;
  add_seed_scene_keys(j, cfg, r.run);
  if (!ctx.out_dir.empty()) {
    std::ostringstream csv;
    csv << "time_s,x_m,z_m\n";
    for (const DrumFrame& f : r.frames)
      for (const auto& [x, z] : f.surface) csv << f.time_s << "," << x << "," << z << "\n";
    write_file_atomic(ctx.out_dir + "/drum_surface.csv", csv.str());
    SideView view;
    view.title = "drum " + std::to_string(spec.speed_rpm) + " rpm: dynamic angle " +
                 std::to_string(r.dynamic_angle_of_repose_deg) + " deg";
    add_spheres(view, r.spheres);
    if (!r.frames.empty() && r.frames.back().fit.ok) {
      const LineFit& f = r.frames.back().fit;
      const double x0 = -0.4 * spec.diameter_m, x1 = 0.4 * spec.diameter_m;
      view.lines.push_back({x0, f.intercept + f.slope * x0, x1, f.intercept + f.slope * x1, "#d62728", "surface fit"});
    }
    write_file_atomic(ctx.out_dir + "/drum.svg", render_svg(view));
  }
  schema.check_metrics(j);
  return j;
}

}  // namespace seedcal
