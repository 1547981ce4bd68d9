// `kind = "direct_shear"`: schema in docs/scenes/direct_shear.md.
#include <algorithm>
#include <numbers>
#include <string>
#include <sstream>

#include "calibrate/scenes/rig_checks.hpp"
#include "calibrate/scenes/scene_schema.hpp"
#include "calibrate/scenes/seed_scene_common.hpp"
#include "solver/scenes/direct_shear.hpp"
#include "store/atomic_file.hpp"

namespace seedcal {

namespace {

// The scene's schema (scene_schema.hpp): its keys, their defaults (DirectShearSpec's), its metrics.
SceneSchema<DirectShearSpec> direct_shear_schema() {
  using S = DirectShearSpec;
  SceneSchema<S> s("direct_shear", "`[direct_shear.paper]` / `[direct_shear.quick]`");
  s.material("box_material", &S::box_material, "the seeds touch the rings, the base and the lid",
             "material of rings, floor and cap")
      .choice("geometry", &S::geometry, {{"zj", ShearBoxGeometry::zj}, {"shells", ShearBoxGeometry::shells}},
              "the rig: `zj` (thick rings, faces, gap, cap) or `shells` (the earlier rig)")
      .number("ring_wall_thickness_m", &S::ring_wall_thickness_m, Range::left_open(0.0, 1.0), "m",
              "zj: the rings' wall thickness; must exceed `shear_displacement_m`")
      .number("ring_gap_m", &S::ring_gap_m, Range::closed(0.0, 1.0), "m",
              "zj: the gap between the rings' faces at the split; at most half `sample_height_m`")
      .number("diameter_m", &S::diameter_m, Range::closed(0.005, 2.0), "m", "box diameter (the rings' bore)")
      .number("sample_height_m", &S::sample_height_m, Range::closed(0.002, 2.0), "m",
              "specimen height (shear plane at half)")
      .number("normal_stress_pa", &S::normal_stress_pa, Range::closed(1.0, 1e8), "Pa", "stress on the cap")
      .number("shear_speed_m_s", &S::shear_speed_m_s, Range::closed(1e-6, 1.0), "m/s", "ring speed")
      .number("shear_displacement_m", &S::shear_displacement_m, Range::closed(1e-4, 1.0), "m", "path length")
      .number("sample_density_kg_m3", &S::sample_density_kg_m3, Range::closed(0.0, 1e4), "kg/m3",
              "weigh the specimen in to this bulk density (0: level by height)")
      .number("pour_height_factor", &S::pour_height_factor, Range::closed(0.5, 20.0), "",
              "guide height, in sample heights")
      .number("consolidation_max_time_s", &S::consolidation_max_time_s, Range::left_open(0.0, 100.0), "s",
              "longest consolidation")
      .number("lid_max_speed_m_s", &S::lid_max_speed_m_s, Range::left_open(0.0, 10.0), "m/s",
              "servo speed limit of the cap (and of a floating upper ring)")
      .number("record_interval_s", &S::record_interval_s, Range::left_open(0.0, 1.0), "s", "curve sampling interval")
      .number("smoothing_m", &S::smoothing_m, Range::closed(0.0, 0.1), "m", "moving-average window of the curve")
      .number("failure_displacement_m", &S::failure_displacement_m, Range::closed(1e-5, 1.0), "m",
              "the peak is searched up to here; with none, the stress here is the strength (GB/T 50123)")
      .flag("upper_ring_fixed", &S::upper_ring_fixed, "hold the upper ring at its height during shear")
      .number("upper_ring_mass_kg", &S::upper_ring_mass_kg, Range::closed(0.0, 1e3), "kg",
              "weight that holds the upper ring on its seat");
  s.metric("shear_strength_pa", "Pa", "the index: peak of the smoothed curve up to the failure displacement")
      .metric("displacement_at_peak_m", "m", "where the peak lies")
      .metric("stress_ratio", "", "strength / mean cap stress")
      .metric("mean_normal_stress_pa", "Pa", "mean normal stress on the cap during shear")
      .metric("normal_stress_pa", "Pa", "the stress asked for (`normal_stress_pa`)")
      .metric("inertial_number", "", "inertial number of the shear (quasi-static below 1e-3)")
      .metric("dilation_m", "m", "cap rise from the start of shear to the end")
      .metric("curve_shape", "",
              "`peak` (the smoothed curve falls after its maximum by more than twice its noise), `plateau` "
              "(it levels off) or `rising` (its maximum lies in the path's last window: the strength is the "
              "stress at the failure displacement of a curve still climbing)")
      .metric("geometry", "", "the rig (`zj` or `shells`)")
      .metric("upper_ring_lift_m", "m", "highest lift of the upper ring off its seat")
      .metric("consolidated_height_m", "m", "the cap's height above the floor when shear starts")
      .metric("seeds_across_split", "", "seeds whose clump reaches across the split plane then")
      .metric("seeds", "", "seeds in the specimen")
      .metric("sample_mass_kg", "kg", "the specimen's mass")
      .metric("sample_bulk_density_kg_m3", "kg/m3", "the specimen's mass over the box volume to the sample height");
  return s;
}

}  // namespace

SchemaTable direct_shear_schema_table() { return direct_shear_schema().doc(); }

nlohmann::json run_direct_shear_scene(TomlReader& root, const SceneContext& ctx) {
  SeedSceneConfig cfg = read_seed_scene(root, ctx.config_path);
  DirectShearSpec spec;
  fill_seed_spec(spec, cfg, ctx);
  const SceneSchema<DirectShearSpec> schema = direct_shear_schema();
  if (auto rig = rig_table(root, "direct_shear", cfg.fidelity)) {
    schema.read(*rig, {cfg.phys, cfg.seed_material}, spec);
    if (spec.ring_gap_m > 0.5 * spec.sample_height_m)
      rig->error("ring_gap_m", "= " + std::to_string(spec.ring_gap_m) + " must be at most half sample_height_m (" +
                                   std::to_string(0.5 * spec.sample_height_m) + ")");
    // The faces must cover the crescents that open between the bores over the whole shear path.
    if (spec.geometry == ShearBoxGeometry::zj && spec.ring_wall_thickness_m <= spec.shear_displacement_m)
      rig->error("ring_wall_thickness_m",
                 "= " + std::to_string(spec.ring_wall_thickness_m) + " must exceed shear_displacement_m (" +
                     std::to_string(spec.shear_displacement_m) +
                     "): the rings' faces cover the gap the upper ring opens only while the ring is wider than its travel");
    warn_if_small_rig(*rig, "diameter_m", "the box's diameter", spec.diameter_m, spec.seeds, kShearBoxDiameter);
    warn_if_small_rig(*rig, "sample_height_m", "the sample's height", spec.sample_height_m, spec.seeds,
                      kShearSampleHeight);
    rig->check_unknown_keys();
  }
  root.check_unknown_keys();
  root.diagnostics().throw_if_any();
  if (ctx.plan) *ctx.plan = plan_direct_shear(spec);  // what the run will simulate (run_plan.hpp)
  if (ctx.check_only) {  // validated: run nothing
    return nlohmann::json::object();
  }

  const DirectShearResult r = run_direct_shear(spec);
  nlohmann::json j;
  j["index_key"] = "shear_strength_pa";
  j["shear_strength_pa"] = r.shear_strength_pa;
  j["displacement_at_peak_m"] = r.displacement_at_peak_m;
  j["stress_ratio"] = r.stress_ratio;
  j["mean_normal_stress_pa"] = r.mean_normal_stress_pa;
  j["normal_stress_pa"] = spec.normal_stress_pa;
  j["inertial_number"] = r.inertial_number;
  j["dilation_m"] = r.dilation_m;
  j["curve_shape"] = r.curve_shape;
  j["geometry"] = to_string(spec.geometry);
  j["upper_ring_lift_m"] = r.upper_ring_lift_m;
  j["consolidated_height_m"] = r.consolidated_height_m;
  j["seeds_across_split"] = r.seeds_across_split;
  j["seeds"] = r.seeds;
  j["sample_mass_kg"] = r.sample_mass_kg;
  j["sample_bulk_density_kg_m3"] = r.sample_mass_kg / (std::numbers::pi * 0.25 * spec.diameter_m * spec.diameter_m * spec.sample_height_m);
  add_seed_scene_keys(j, cfg, r.run);
  if (!ctx.out_dir.empty()) {
    std::ostringstream csv;
    csv << "displacement_m,shear_stress_pa,smoothed_shear_stress_pa,normal_stress_pa,lid_height_m,upper_ring_lift_m\n";
    for (const ShearSample& s : r.curve)
      csv << s.displacement_m << "," << s.shear_stress_pa << "," << s.smoothed_shear_stress_pa << ","
          << s.normal_stress_pa << "," << s.lid_height_m << "," << s.upper_ring_lift_m << "\n";
    write_file_atomic(ctx.out_dir + "/direct_shear_curve.csv", csv.str());
    SideView view;
    view.title = "direct shear (" + std::string(to_string(spec.geometry)) + " rig) at the end of shear: strength " +
                 std::to_string(r.shear_strength_pa / 1e3) + " kPa (shear plane in red)";
    add_spheres(view, r.spheres);
    const double R = 0.5 * spec.diameter_m;
    view.lines.push_back({-R, 0.5 * spec.sample_height_m, R + spec.shear_displacement_m, 0.5 * spec.sample_height_m, "#d62728", "shear plane"});
    // The rings and the cap in section, the upper ring's guide cut off a seed above the cap.
    const double clip = r.consolidated_height_m + 0.5 * spec.sample_height_m;
    for (const auto& [x0, z0, x1, z1] : r.rig_outline_m) {
      const double top = std::min(z1, clip);
      if (z0 > clip) continue;
      const std::string steel = "#555555";
      view.lines.push_back({x0, z0, x1, z0, steel, ""});
      if (top > z0) {
        view.lines.push_back({x0, z0, x0, top, steel, ""});
        view.lines.push_back({x1, z0, x1, top, steel, ""});
        view.lines.push_back({x0, top, x1, top, steel, ""});
      }
    }
    write_file_atomic(ctx.out_dir + "/direct_shear.svg", render_svg(view));
  }
  schema.check_metrics(j);
  return j;
}

}  // namespace seedcal
