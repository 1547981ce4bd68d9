// `kind = "direct_shear"`: schema in docs/scenes/direct_shear.md.
#include <algorithm>
#include <numbers>
#include <string>
#include <sstream>

#include "calibrate/scenes/rig_checks.hpp"
#include "calibrate/scenes/seed_scene_common.hpp"
#include "solver/scenes/direct_shear.hpp"
#include "store/atomic_file.hpp"

namespace seedcal {

nlohmann::json run_direct_shear_scene(TomlReader& root, const SceneContext& ctx) {
  SeedSceneConfig cfg = read_seed_scene(root, ctx.config_path);
  DirectShearSpec spec;
  fill_seed_spec(spec, cfg, ctx);
  if (auto rig = rig_table(root, "direct_shear", cfg.fidelity)) {
    spec.box_material = cfg.phys.material(*rig, "box_material", rig->string("box_material"));
    cfg.require_wall_interaction(*rig, "box_material", spec.box_material,
                                 "the seeds touch the rings, the base and the lid");
    spec.diameter_m = rig->number("diameter_m", Range::closed(0.005, 2.0), spec.diameter_m);
    spec.sample_height_m = rig->number("sample_height_m", Range::closed(0.002, 2.0), spec.sample_height_m);
    spec.normal_stress_pa = rig->number("normal_stress_pa", Range::closed(1.0, 1e8), spec.normal_stress_pa);
    spec.shear_speed_m_s = rig->number("shear_speed_m_s", Range::closed(1e-6, 1.0), spec.shear_speed_m_s);
    spec.shear_displacement_m = rig->number("shear_displacement_m", Range::closed(1e-4, 1.0), spec.shear_displacement_m);
    spec.sample_density_kg_m3 = rig->number("sample_density_kg_m3", Range::closed(0.0, 1e4), spec.sample_density_kg_m3);
    spec.pour_height_factor = rig->number("pour_height_factor", Range::closed(0.5, 20.0), spec.pour_height_factor);
    spec.consolidation_max_time_s = rig->number("consolidation_max_time_s", Range::left_open(0.0, 100.0), spec.consolidation_max_time_s);
    spec.lid_max_speed_m_s = rig->number("lid_max_speed_m_s", Range::left_open(0.0, 10.0), spec.lid_max_speed_m_s);
    spec.record_interval_s = rig->number("record_interval_s", Range::left_open(0.0, 1.0), spec.record_interval_s);
    spec.smoothing_m = rig->number("smoothing_m", Range::closed(0.0, 0.1), spec.smoothing_m);
    spec.failure_displacement_m = rig->number("failure_displacement_m", Range::closed(1e-5, 1.0), spec.failure_displacement_m);
    spec.upper_ring_fixed = rig->boolean("upper_ring_fixed", spec.upper_ring_fixed);
    spec.upper_ring_mass_kg = rig->number("upper_ring_mass_kg", Range::closed(0.0, 1e3), spec.upper_ring_mass_kg);
    spec.geometry = rig->choice("geometry", {"zj", "shells"}, "zj") == "zj" ? ShearBoxGeometry::zj
                                                                          : ShearBoxGeometry::shells;
    spec.ring_wall_thickness_m = rig->number("ring_wall_thickness_m", Range::left_open(0.0, 1.0), spec.ring_wall_thickness_m);
    spec.ring_gap_m = rig->number("ring_gap_m", Range::closed(0.0, 0.5 * spec.sample_height_m), spec.ring_gap_m);
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
  return j;
}

}  // namespace seedcal
