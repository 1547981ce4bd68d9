// `seedcal clump build|info|table|moisture`: clump models from measured seed dimensions
// (docs/clumps.md).
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "app/commands.hpp"
#include "calibrate/clumps/clump_build.hpp"
#include "calibrate/clumps/moisture.hpp"
#include "calibrate/clumps/size_distribution.hpp"
#include "store/atomic_file.hpp"
#include "store/errors.hpp"

namespace seedcal {
namespace {

struct BuildArgs {
  std::string variety, scan, unit, align = "principal", method, out, name;
  int spheres = 0;
  // Scanner copies of one vertex differ in their last digits, far below a micrometre; a seed's
  // scan has triangle edges of a tenth of a millimetre and more.
  double weld_m = 1e-6;
  double smoothness = -1.0, soak_hours = 0.0, density = 0.0, min_radius_m = 0.0;
};

std::string build_command_line(const BuildArgs& a) {
  std::ostringstream s;
  s << "seedcal clump build";
  if (!a.variety.empty()) s << " --variety " << a.variety;
  if (!a.scan.empty())
    s << " --scan " << a.scan << " --unit " << a.unit << " --weld-m " << a.weld_m << " --align " << a.align
      << " --density " << a.density;
  s << " --method " << a.method;
  if (a.spheres > 0) s << " --spheres " << a.spheres;
  if (a.smoothness >= 0) s << " --smoothness " << a.smoothness;
  if (a.min_radius_m > 0) s << " --min-radius-m " << a.min_radius_m;
  if (a.soak_hours > 0) s << " --soak-hours " << a.soak_hours;
  return s.str();
}

void run_build(const BuildArgs& a) {
  std::vector<std::string> problems;
  if (a.variety.empty() == a.scan.empty()) problems.push_back("clump build: give --variety NAME or --scan FILE (one of them)");
  if (!a.scan.empty() && !(a.density > 0.0)) problems.push_back("clump build: --scan needs --density KG_M3 > 0");
  if (!a.scan.empty() && a.unit.empty())
    problems.push_back("clump build: --scan needs --unit m or --unit mm (the unit of the scan's coordinates; "
                       "scanners often write millimetres)");
  if (a.scan.empty() && !a.unit.empty()) problems.push_back("clump build: --unit goes with --scan");
  if (a.method == "manual" && (a.spheres < 5 || a.spheres > 15 || a.spheres % 2 == 0))
    problems.push_back("clump build: --method manual --spheres " + std::to_string(a.spheres) +
                       ": must be odd, 5 to 15");
  if (a.method == "auto" && (a.spheres > 0) == (a.smoothness >= 0))
    problems.push_back("clump build: --method auto needs exactly one of --spheres N (1..5000) or --smoothness S (0..5)");
  if (a.method == "auto" && a.smoothness > 5) problems.push_back("clump build: --smoothness " + std::to_string(a.smoothness) + ": must be in [0, 5]");
  if (a.method == "auto" && (a.spheres < 0 || a.spheres > 5000)) problems.push_back("clump build: --spheres must be in [1, 5000]");
  if (!problems.empty()) throw InputError(problems);
  ClumpShapeInfo info;
  double density = a.density;
  Variety v;
  if (!a.variety.empty()) {
    v = read_variety(a.variety);
    info = variety_shape(v, a.soak_hours);
    density = v.density_kg_m3;
  } else {
    info.kind = "scan";
    info.scan = {a.scan, metres_per_unit(a.unit), a.weld_m, a.align == "principal"};
  }
  const auto shape = make_shape(info);
  // The clump file names the scan relative to its own folder (clump_file.hpp).
  if (info.kind == "scan" && std::filesystem::path(a.scan).is_relative()) {
    const auto dir = std::filesystem::absolute(std::filesystem::path(a.out)).parent_path();
    info.scan.path = std::filesystem::relative(std::filesystem::absolute(a.scan), dir).string();
  }
  const auto t0 = std::chrono::steady_clock::now();
  ClumpModel m = build_clump(*shape, info, density, {a.method, a.spheres, a.smoothness, a.min_radius_m});
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  m.name = a.name.empty() ? std::filesystem::path(a.out).stem().string() : a.name;
  m.variety = v.name;
  m.variety_file = v.file;
  m.soak_hours = a.soak_hours;
  m.seedcal_version = version_string();
  m.command = build_command_line(a);
  if (const auto dir = std::filesystem::path(a.out).parent_path(); !dir.empty())
    std::filesystem::create_directories(dir);
  write_clump_file(a.out, m);
  std::printf("%s: %zu spheres, volume %.5e m3 (shape %.5e m3, %.2f %%), IoU %.4f, built in %.2f s\n",
              a.out.c_str(), m.spheres.size(), m.volume_m3, m.target_volume_m3,
              100.0 * m.volume_m3 / m.target_volume_m3, m.iou, secs);
  if (info.kind == "scan") std::printf("  shape: %s\n", shape->describe().c_str());
}

nlohmann::json info_json(const std::string& path) {
  ClumpModel m;
  try {
    m = read_clump_file(path);
  } catch (const InputError&) {
    throw;
  }
  const auto shape = make_shape(m.shape);
  const auto in_shape = m.spheres_in_shape_frame();
  const UnionMassProperties mp = union_mass_properties(in_shape);
  double iou_err = 0.0;
  const Overlap ov = shape_overlap_converged(*shape, in_shape, 1e-4, &iou_err);
  const double finest = finest_auto_volume_m3(*shape);
  Vec3 lo_s = in_shape[0].centre_m, hi_s = lo_s, lo_b = m.spheres[0].centre_m, hi_b = lo_b;
  for (std::size_t i = 0; i < in_shape.size(); ++i) {
    const Vec3 r = Vec3::Constant(in_shape[i].radius_m);
    lo_s = lo_s.cwiseMin(in_shape[i].centre_m - r);
    hi_s = hi_s.cwiseMax(in_shape[i].centre_m + r);
    lo_b = lo_b.cwiseMin(m.spheres[i].centre_m - r);
    hi_b = hi_b.cwiseMax(m.spheres[i].centre_m + r);
  }
  const Vec3 pi = m.density_kg_m3 * mp.principal_moments_unit_density;
  const Vec3 bs = hi_s - lo_s, bb = hi_b - lo_b;
  return {{"file", path},
          {"name", m.name},
          {"method", m.method},
          {"spheres", m.spheres.size()},
          {"volume_m3", mp.volume_m3},
          {"volume_rel_error", mp.volume_rel_error_bound},
          {"finest_auto_volume_m3", finest},
          {"volume_ratio_to_finest_auto", mp.volume_m3 / finest},
          {"target_volume_m3", shape->volume_m3()},
          {"volume_ratio_to_target", mp.volume_m3 / shape->volume_m3()},
          {"iou", ov.iou()},
          {"iou_error", iou_err},
          {"shape", shape->describe()},
          {"density_kg_m3", m.density_kg_m3},
          {"mass_kg", m.density_kg_m3 * mp.volume_m3},
          {"principal_inertia_kg_m2", {pi.x(), pi.y(), pi.z()}},
          {"bounding_box_m", {bs.x(), bs.y(), bs.z()}},
          {"bounding_box_body_frame_m", {bb.x(), bb.y(), bb.z()}},
          {"min_radius_m", [&] { double r = 1e9; for (const auto& s : m.spheres) r = std::min(r, s.radius_m); return r; }()},
          {"command", m.command}};
}

void run_info(const std::string& path, bool json) {
  const nlohmann::json j = info_json(path);
  if (json) {
    std::cout << j.dump(2) << "\n";
    return;
  }
  const auto& pi = j["principal_inertia_kg_m2"];
  const auto& bb = j["bounding_box_m"];
  std::printf("%s (%s, %s)\n", path.c_str(), j["name"].get<std::string>().c_str(), j["method"].get<std::string>().c_str());
  std::printf("  spheres                 %d\n", j["spheres"].get<int>());
  std::printf("  volume of the union     %.5e m3 (estimated error %.1e)\n", j["volume_m3"].get<double>(), j["volume_rel_error"].get<double>());
  std::printf("  ratio to finest auto    %.2f %% (finest: %.5e m3)\n", 100 * j["volume_ratio_to_finest_auto"].get<double>(), j["finest_auto_volume_m3"].get<double>());
  std::printf("  target shape            %s, %.5e m3; clump/target %.2f %%\n", j["shape"].get<std::string>().c_str(), j["target_volume_m3"].get<double>(), 100 * j["volume_ratio_to_target"].get<double>());
  std::printf("  intersection over union %.4f\n", j["iou"].get<double>());
  std::printf("  mass                    %.5e kg at %.0f kg/m3\n", j["mass_kg"].get<double>(), j["density_kg_m3"].get<double>());
  std::printf("  principal inertia       %.4e %.4e %.4e kg m2\n", pi[0].get<double>(), pi[1].get<double>(), pi[2].get<double>());
  std::printf("  bounding box            %.3f x %.3f x %.3f mm (shape frame)\n", 1e3 * bb[0].get<double>(), 1e3 * bb[1].get<double>(), 1e3 * bb[2].get<double>());
}

struct TableRow {
  std::string filling;
  int paper_spheres = 0;
  double paper_volume = 0, paper_ratio = 0;
  std::string request;
  ClumpModel model;
};

void run_table(const std::string& variety, bool json) {
  const Variety v = read_variety(variety);
  const ClumpShapeInfo info = variety_shape(v);
  const auto shape = make_shape(info);
  std::vector<TableRow> rows;
  auto paper = [&](const std::string& filling, int n) -> const PaperClump* {
    for (const auto& p : v.paper_clumps) if (p.filling == filling && p.spheres == n) return &p;
    return nullptr;
  };
  for (const auto& p : v.paper_clumps) {
    if (p.filling != "manual") continue;
    TableRow r{"manual", p.spheres, p.volume_m3, p.ratio, "--method manual --spheres " + std::to_string(p.spheres), {}};
    r.model = build_clump(*shape, info, v.density_kg_m3, {"manual", p.spheres, -1.0});
    rows.push_back(std::move(r));
  }
  // The paper's automatic models: the smallest by sphere count, then smoothness 2 and 0.
  std::vector<const PaperClump*> autos;
  for (const auto& p : v.paper_clumps) if (p.filling == "automatic") autos.push_back(&p);
  std::sort(autos.begin(), autos.end(), [](auto* a, auto* b) { return a->spheres < b->spheres; });
  for (std::size_t i = 0; i < autos.size(); ++i) {
    const PaperClump* p = autos[i];
    TableRow r{"automatic", p->spheres, p->volume_m3, p->ratio, "", {}};
    BuildRequest q{"auto", 0, -1.0};
    if (i + 2 < autos.size()) { q.spheres = p->spheres; r.request = "--method auto --spheres " + std::to_string(p->spheres); }
    else if (i + 2 == autos.size()) { q.smoothness = 2; r.request = "--method auto --smoothness 2"; }
    else { q.smoothness = 0; r.request = "--method auto --smoothness 0"; }
    r.model = build_clump(*shape, info, v.density_kg_m3, q);
    rows.push_back(std::move(r));
  }
  (void)paper;
  double finest = 0.0;
  for (const auto& r : rows) if (r.request == "--method auto --smoothness 0") finest = r.model.volume_m3;
  if (finest <= 0.0) finest = finest_auto_volume_m3(*shape);
  nlohmann::json j = {{"variety", v.name}, {"variety_file", v.file}, {"shape", shape->describe()},
                      {"target_volume_m3", shape->volume_m3()}, {"finest_auto_volume_m3", finest}, {"rows", nlohmann::json::array()}};
  for (const auto& r : rows) {
    nlohmann::json row = {{"filling", r.filling}, {"paper_spheres", r.paper_spheres},
                          {"paper_volume_m3", r.paper_volume}, {"paper_ratio", r.paper_ratio},
                          {"request", r.request}, {"spheres", r.model.spheres.size()},
                          {"volume_m3", r.model.volume_m3}, {"ratio", r.model.volume_m3 / finest},
                          {"volume_vs_paper", r.model.volume_m3 / r.paper_volume},
                          {"iou", r.model.iou}};
    const PaperClump* p = paper(r.filling, r.paper_spheres);
    if (p && !p->flag.empty()) row["paper_flag"] = p->flag;
    j["rows"].push_back(row);
  }
  if (json) {
    std::cout << j.dump(2) << "\n";
    return;
  }
  std::printf("%s: Table 4 of the paper beside seedcal's models of %s (%.4e m3)\n", v.name.c_str(),
              shape->describe().c_str(), shape->volume_m3());
  std::printf("%-10s | %7s %12s %8s | %-30s %7s %12s %8s %9s %6s\n", "filling", "spheres", "volume m3", "ratio",
              "seedcal model", "spheres", "volume m3", "ratio", "vs paper", "IoU");
  for (const auto& row : j["rows"]) {
    std::printf("%-10s | %7d %12.5e %7.2f%% | %-30s %7d %12.5e %7.2f%% %8.1f%% %6.3f%s\n",
                row["filling"].get<std::string>().c_str(), row["paper_spheres"].get<int>(),
                row["paper_volume_m3"].get<double>(), 100 * row["paper_ratio"].get<double>(),
                row["request"].get<std::string>().c_str(), row["spheres"].get<int>(),
                row["volume_m3"].get<double>(), 100 * row["ratio"].get<double>(),
                100 * (row["volume_vs_paper"].get<double>() - 1), row["iou"].get<double>(),
                row.contains("paper_flag") ? "  (paper ratio flagged)" : "");
  }
  std::printf("ratio: volume / the same source's finest automatic model (paper: its 100 %% row; seedcal: smoothness 0)\n");
}

void run_moisture(const std::string& variety, bool json) {
  const Variety v = read_variety(variety);
  const ModulusFit f = fit_modulus(v);
  const ScaleDistribution sd = width_scale_distribution(v);
  auto fit_json = [](const LineFit& l) {
    return nlohmann::json{{"model", l.model}, {"n", l.n}, {"c0", l.c0}, {"c1", l.c1}, {"r2", l.r2},
                          {"sumsq", l.sumsq}, {"se_c1", l.se_c1}, {"t_c1", l.t_c1}, {"p_c1", l.p_c1}};
  };
  nlohmann::json j = {{"variety", v.name}, {"linear", fit_json(f.linear)}, {"log_linear", fit_json(f.log_linear)},
                      {"flag", f.flag}, {"youngs_modulus_pa_at_variety_moisture", f.youngs_modulus_pa(v.moisture_fraction)},
                      {"scale_distribution", {{"mean", sd.mean}, {"sd", sd.sd}, {"lo", sd.lo}, {"hi", sd.hi}}},
                      {"soaking_growth", nlohmann::json::array()}};
  for (double h : v.soak_hours) {
    const Vec3 g = soaking_growth(v, h);
    j["soaking_growth"].push_back({{"hours", h}, {"length", g.x()}, {"width", g.y()}, {"thickness", g.z()}});
  }
  if (json) {
    std::cout << j.dump(2) << "\n";
    return;
  }
  std::printf("%s: Young's modulus against moisture fraction w (Table 3, %d points)\n", v.name.c_str(), f.linear.n);
  for (const LineFit* l : {&f.linear, &f.log_linear})
    std::printf("  %-18s c0 = %.4g, c1 = %.4g (se %.3g, p = %.3g), R2 = %.3f\n", l->model.c_str(), l->c0, l->c1,
                l->se_c1, l->p_c1, l->r2);
  if (!f.flag.empty()) std::printf("  flag: %s\n", f.flag.c_str());
  std::printf("  E at the variety's moisture %.3f: %.4g Pa (log-linear fit)\n", v.moisture_fraction,
              f.youngs_modulus_pa(v.moisture_fraction));
  std::printf("  size distribution (factory scale): mean %.3f sd %.4f in [%.3f, %.3f]\n", sd.mean, sd.sd, sd.lo, sd.hi);
  for (const auto& g : j["soaking_growth"])
    std::printf("  soaked %4.0f h: L x %.3f, W x %.3f, T x %.3f\n", g["hours"].get<double>(), g["length"].get<double>(),
                g["width"].get<double>(), g["thickness"].get<double>());
}

}  // namespace

void add_clump_command(CLI::App& app, GlobalOptions& g) {
  CLI::App* sub = app.add_subcommand("clump", "build and inspect multi-sphere clump models of seeds");
  add_common_options(*sub, g);
  sub->require_subcommand(1);

  auto b = std::make_shared<BuildArgs>();
  CLI::App* build = sub->add_subcommand("build", "fill a seed shape with spheres and write a clump file");
  build->add_option("--variety", b->variety, "variety name (data/varieties/NAME.toml) or file");
  build->add_option("--scan,--stl", b->scan, "closed surface of a scanned seed (.stl, .ply or .obj) instead of a variety");
  build->add_option("--unit", b->unit, "unit of the scan's coordinates (required with --scan)")->check(CLI::IsMember({"m", "mm"}));
  build->add_option("--weld-m", b->weld_m, "scan vertices closer than this become one, m")
      ->check(CLI::Range(0.0, 1e-3))->capture_default_str();
  build->add_option("--align", b->align, "principal: turn the scan so that x is its length axis; none: keep the scanner's frame")
      ->check(CLI::IsMember({"principal", "none"}))->capture_default_str();
  build->add_option("--density", b->density, "density in kg/m3 (with --scan)");
  build->add_option("--method", b->method, "manual or auto")->required()->check(CLI::IsMember({"manual", "auto"}));
  build->add_option("--spheres", b->spheres, "sphere count: manual odd 5..15; auto a target 1..5000");
  build->add_option("--smoothness", b->smoothness, "auto: 0 (finest, ~1,800 spheres) .. 5 (coarsest)");
  build->add_option("--min-radius-m", b->min_radius_m,
                    "auto: no sphere smaller than this, m (a floor under the smoothness's or the count's; docs/clumps.md)")
      ->check(CLI::Range(0.0, 0.1));
  build->add_option("--soak-hours", b->soak_hours, "scale the variety's dimensions by Table 2 growth")->check(CLI::Range(0.0, 1000.0));
  build->add_option("--name", b->name, "model name (default: the output file's stem)");
  build->add_option("--out", b->out, "clump file to write (TOML)")->required();
  build->callback([b] { run_build(*b); });

  auto info_path = std::make_shared<std::string>();
  auto info_json_flag = std::make_shared<bool>(false);
  CLI::App* info = sub->add_subcommand("info", "volume, IoU, inertia and size of a clump file");
  info->add_option("file", *info_path, "clump file (TOML)")->required();
  info->add_flag("--json", *info_json_flag, "print one JSON object");
  info->callback([info_path, info_json_flag] { run_info(*info_path, *info_json_flag); });

  auto tv = std::make_shared<std::string>();
  auto tj = std::make_shared<bool>(false);
  CLI::App* table = sub->add_subcommand("table", "the paper's Table 4 beside seedcal's models of a variety");
  table->add_option("--variety", *tv, "variety name or file")->required();
  table->add_flag("--json", *tj, "print one JSON object");
  table->callback([tv, tj] { run_table(*tv, *tj); });

  auto mv = std::make_shared<std::string>();
  auto mj = std::make_shared<bool>(false);
  CLI::App* moist = sub->add_subcommand("moisture", "Young's modulus vs moisture fit, soaking growth, size distribution");
  moist->add_option("--variety", *mv, "variety name or file")->required();
  moist->add_flag("--json", *mj, "print one JSON object");
  moist->callback([mv, mj] { run_moisture(*mv, *mj); });
}

}  // namespace seedcal
