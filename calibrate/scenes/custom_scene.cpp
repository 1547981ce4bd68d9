// `kind = "custom"`: schema in docs/scenes/custom.md.
#include <cmath>
#include <numbers>
#include <sstream>

#include "calibrate/output/wall_section.hpp"
#include "calibrate/scenes/custom_config.hpp"
#include "calibrate/scenes/seed_scene_common.hpp"
#include "store/atomic_file.hpp"

namespace seedcal {
namespace {
// Named: this file compiles in a unity batch with other files (cmake/build_speed.cmake), whose
// helpers in their anonymous namespaces must not clash with these.
namespace custom_scene_output {

const char* kind_name(CustomMeasure::Kind k) {
  switch (k) {
    case CustomMeasure::Kind::mass_in_region: return "mass_in_region";
    case CustomMeasure::Kind::discharge_rate: return "discharge_rate";
    case CustomMeasure::Kind::surface_height: return "surface_height";
  }
  return "";
}

// The headline key a measurement adds to the top level of metrics.json.
std::string headline_key(const CustomMeasure& m) {
  switch (m.kind) {
    case CustomMeasure::Kind::mass_in_region: return m.name + "_final_kg";
    case CustomMeasure::Kind::discharge_rate: return m.name + "_kg_s";
    case CustomMeasure::Kind::surface_height: return m.name + "_final_mean_height_m";
  }
  return m.name;
}

double mean(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

nlohmann::json measurement_json(const CustomMeasure& m, const CustomSeries& s, nlohmann::json& top) {
  nlohmann::json j;
  j["kind"] = kind_name(m.kind);
  j["samples"] = s.time_s.size();
  switch (m.kind) {
    case CustomMeasure::Kind::mass_in_region:
      j["region_lo_m"] = {m.region.lo_m.x(), m.region.lo_m.y(), m.region.lo_m.z()};
      j["region_hi_m"] = {m.region.hi_m.x(), m.region.hi_m.y(), m.region.hi_m.z()};
      j["initial_kg"] = s.value.empty() ? 0.0 : s.value.front();
      j["final_kg"] = s.value.empty() ? 0.0 : s.value.back();
      break;
    case CustomMeasure::Kind::discharge_rate:
      j["rate_kg_s"] = s.rate.rate_kg_s;
      j["fit_ok"] = s.rate.ok;
      j["fit_r2"] = s.rate.fit.r2;
      j["fit_points"] = s.rate.fit.points;
      j["fit_window_s"] = {s.rate.t_begin_s, s.rate.t_end_s};
      j["crossed_kg"] = s.value.empty() ? 0.0 : s.value.back();
      if (!s.rate.ok)
        top["warnings"].push_back(m.name + ": fewer than 3 samples in the steady window (crossed " +
                                  std::to_string(j["crossed_kg"].get<double>()) +
                                  " kg): no steady rate; run longer or sample more often");
      break;
    case CustomMeasure::Kind::surface_height: {
      nlohmann::json pts = nlohmann::json::array();
      for (const Vec3& p : surface_line_points(m)) pts.push_back({p.x(), p.y(), p.z()});
      j["points_m"] = pts;
      j["probe_radius_m"] = m.probe_radius_m;
      j["initial_height_m"] = s.heights.empty() ? std::vector<double>{} : s.heights.front();
      j["final_height_m"] = s.heights.empty() ? std::vector<double>{} : s.heights.back();
      j["final_mean_height_m"] = s.heights.empty() ? 0.0 : mean(s.heights.back());
      break;
    }
  }
  top[headline_key(m)] = m.kind == CustomMeasure::Kind::mass_in_region   ? j["final_kg"]
                         : m.kind == CustomMeasure::Kind::discharge_rate ? j["rate_kg_s"]
                                                                         : j["final_mean_height_m"];
  return j;
}

std::string series_csv(const CustomMeasure& m, const CustomSeries& s) {
  std::ostringstream csv;
  csv.precision(9);
  if (m.kind == CustomMeasure::Kind::surface_height) {
    const std::vector<Vec3> pts = surface_line_points(m);
    csv << "time_s,point,x_m,y_m,height_m\n";
    for (std::size_t k = 0; k < s.heights.size(); ++k)
      for (std::size_t p = 0; p < pts.size(); ++p)
        csv << s.time_s[k] << "," << p << "," << pts[p].x() << "," << pts[p].y() << "," << s.heights[k][p] << "\n";
  } else {
    csv << "time_s," << (m.kind == CustomMeasure::Kind::mass_in_region ? "mass_kg" : "crossed_kg") << "\n";
    for (std::size_t k = 0; k < s.time_s.size(); ++k) csv << s.time_s[k] << "," << s.value[k] << "\n";
  }
  return csv.str();
}

// Side view (x, z) at the picture time: the seeds, the walls cut by the plane through the fill
// region's centre, the regions, discharge planes and surface lines with their last profile.
std::string picture(const CustomSpec& spec, const CustomResult& r) {
  SideView view;
  std::ostringstream title;
  title.precision(3);
  title << "custom scene at t = " << r.picture_time_s << " s into the run";
  view.title = title.str();
  add_spheres(view, r.spheres);
  const BoxRegion& f = spec.fill.region;
  const Vec3 centre = 0.5 * (f.lo_m + f.hi_m);
  double reach = 0.5 * (f.hi_m - f.lo_m).norm();
  for (const auto& body : r.spheres)
    for (const auto& [p, rad] : body) reach = std::max(reach, (p - centre).norm() + rad);
  for (SvgLine& l : wall_section(r.walls, centre.y(), centre, reach, "#444444")) view.lines.push_back(l);
  const auto rect = [&view](const BoxRegion& b, const std::string& colour, const std::string& label) {
    const double x0 = b.lo_m.x(), x1 = b.hi_m.x(), z0 = b.lo_m.z(), z1 = b.hi_m.z();
    view.lines.push_back({x0, z0, x1, z0, colour, ""});
    view.lines.push_back({x1, z0, x1, z1, colour, ""});
    view.lines.push_back({x1, z1, x0, z1, colour, label});
    view.lines.push_back({x0, z1, x0, z0, colour, ""});
  };
  rect(f, "#2ca02c", "fill");
  for (std::size_t k = 0; k < spec.measures.size(); ++k) {
    const CustomMeasure& m = spec.measures[k];
    if (m.kind == CustomMeasure::Kind::mass_in_region) rect(m.region, "#1f77b4", m.name);
    if (m.kind == CustomMeasure::Kind::discharge_rate) {
      // The plane's trace in the view: the line through its point along (n_z, -n_x).
      const Eigen::Vector2d d = Eigen::Vector2d(m.normal.z(), -m.normal.x()).normalized() * reach;
      if (std::isfinite(d.x()))
        view.lines.push_back({m.point_m.x() - d.x(), m.point_m.z() - d.y(), m.point_m.x() + d.x(),
                              m.point_m.z() + d.y(), "#d62728", m.name});
    }
    if (m.kind == CustomMeasure::Kind::surface_height && !r.series[k].heights.empty()) {
      const std::vector<Vec3> pts = surface_line_points(m);
      const std::vector<double>& h = r.series[k].heights.back();
      for (std::size_t p = 0; p + 1 < pts.size(); ++p)
        view.lines.push_back({pts[p].x(), pts[p].z() + h[p], pts[p + 1].x(), pts[p + 1].z() + h[p + 1], "#ff7f0e",
                              p == 0 ? m.name : ""});
    }
  }
  return render_svg(view);
}

}  // namespace custom_scene_output
}  // namespace

nlohmann::json run_custom_scene(TomlReader& root, const SceneContext& ctx) {
  using namespace custom_scene_output;
  SeedSceneConfig cfg = read_seed_scene(root, ctx.config_path);
  CustomSpec spec = read_custom_rig(root, cfg, ctx.config_path);
  fill_seed_spec(spec, cfg, ctx);
  root.check_unknown_keys();
  root.diagnostics().throw_if_any();
  if (ctx.plan) *ctx.plan = plan_custom(spec);  // what the run will simulate (run_plan.hpp)
  if (ctx.check_only) {  // validated: run nothing
    return nlohmann::json::object();
  }

  const CustomResult r = run_custom(spec);
  nlohmann::json j;
  j["index_key"] = headline_key(spec.measures.front());
  nlohmann::json measures;
  for (std::size_t k = 0; k < spec.measures.size(); ++k)
    measures[spec.measures[k].name] = measurement_json(spec.measures[k], r.series[k], j);
  j["measurements"] = measures;
  const double rho = spec.physics.materials[spec.seeds.body.material].density_kg_m3;
  // d_v = (6 V / pi)^(1/3) of the mean seed volume (seed_bed.hpp): the d of Beverloo's correlation.
  j["seed_volume_equivalent_diameter_m"] = std::cbrt(6.0 * seed_volume_m3(spec.seeds, rho) / std::numbers::pi);
  j["seeds_poured"] = r.seeds_poured;
  j["mass_poured_kg"] = r.mass_poured_kg;
  j["seeds_removed"] = r.seeds_removed;
  j["settle_reason"] = r.settle_reason;
  j["run_time_s"] = spec.run_time_s;
  add_seed_scene_keys(j, cfg, r.run);
  if (!ctx.out_dir.empty()) {
    for (std::size_t k = 0; k < spec.measures.size(); ++k)
      write_file_atomic(ctx.out_dir + "/custom_" + spec.measures[k].name + ".csv",
                        series_csv(spec.measures[k], r.series[k]));
    write_file_atomic(ctx.out_dir + "/custom.svg", picture(spec, r));
  }
  return j;
}

}  // namespace seedcal
