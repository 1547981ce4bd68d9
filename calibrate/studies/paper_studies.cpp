#include "calibrate/studies/paper_studies.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "calibrate/clumps/moisture.hpp"
#include "calibrate/clumps/variety.hpp"
#include "calibrate/scenes/scene_file.hpp"
#include "calibrate/studies/study_stats.hpp"

namespace seedcal {
namespace {

std::vector<std::string> with(std::vector<std::string> sets, std::initializer_list<std::string> more) {
  sets.insert(sets.end(), more.begin(), more.end());
  return sets;
}

std::string youngs_modulus_set(double e) {
  char set[96];
  std::snprintf(set, sizeof set, "materials.seed.youngs_modulus_pa=%.17g", e);
  return set;
}

std::string sub_dir(const PaperStudyOptions& o, const std::string& name) {
  return o.out_dir.empty() ? std::string() : o.out_dir + "/scenes/" + name;
}

// Free drop: rebound height (m) and contact points at impact, every repeat.
nlohmann::json free_drop(const PaperStudyOptions& o, const std::vector<std::string>& sets, const std::string& name) {
  const auto m = run_scene_file(o.free_drop_scene, sets, o.threads, o.seed, o.repeats, sub_dir(o, name));
  if (o.progress) o.progress->scene_done(o.free_drop_scene, sets, m);
  nlohmann::json j = {{"rebound_height_m", sample_stats(per_run(m, "rebound_height_m"))},
                      {"contact_points", sample_stats(per_run(m, "contact_points"))},
                      {"cpu_seconds", m.value("cpu_seconds", 0.0)},
                      {"status", m.value("status", "ok")}};
  if (m.contains("failure")) j["failure"] = m["failure"];
  return j;
}

}  // namespace

std::vector<PlannedRuns> multicontact_plan(const PaperStudyOptions& o) {
  std::vector<PlannedRuns> plan;
  for (const char* model : {"hertz_mindlin", "hmnr"})
    plan.push_back({std::string("free drop, ") + model, o.free_drop_scene,
                    with(o.sets, {std::string("contact.model=") + model}), o.repeats});
  if (!o.drum_scene.empty())
    for (const char* model : {"hertz_mindlin", "hmnr"})
      plan.push_back({std::string("drum, ") + model, o.drum_scene, with(o.sets, {std::string("contact.model=") + model}),
                      o.drum_repeats});
  return plan;
}

std::vector<PlannedRuns> stiffness_plan(const PaperStudyOptions& o) {
  std::vector<PlannedRuns> plan;
  for (const double e : o.youngs_moduli_pa) {
    const std::string set = youngs_modulus_set(e);
    plan.push_back({"free drop, " + set, o.free_drop_scene, with(o.sets, {"contact.model=hmnr", set}), o.repeats});
  }
  return plan;
}

nlohmann::json multicontact_study(const PaperStudyOptions& o) {
  nlohmann::json j = {{"study", "multicontact"}, {"free_drop_scene", o.free_drop_scene}, {"sets", o.sets},
                      {"repeats", o.repeats}, {"seed", o.seed}};
  // The same seeds under both models: the same orientations, so the difference is the model's.
  const auto hm = free_drop(o, with(o.sets, {"contact.model=hertz_mindlin"}), "free_drop_hm");
  const auto hmnr = free_drop(o, with(o.sets, {"contact.model=hmnr"}), "free_drop_hmnr");
  const double a = mean_of(hm["rebound_height_m"]), b = mean_of(hmnr["rebound_height_m"]);
  j["free_drop"] = {{"hertz_mindlin", hm}, {"hmnr", hmnr},
                    {"rebound_relative_difference", number_or_null((b - a) / a)},
                    {"paper", {{"hertz_mindlin_rebound_height_m", 0.04150}, {"hertz_mindlin_sd_m", 0.00836},
                               {"hmnr_rebound_height_m", 0.05800}, {"hmnr_sd_m", 0.00676},
                               {"note", "paper section 4, 188-sphere automatic Jinong 1 model, 10 repeats"}}}};
  if (!o.drum_scene.empty()) {
    auto drum = [&](const std::string& model, const std::string& name) {
      const std::vector<std::string> sets = with(o.sets, {"contact.model=" + model});
      const auto m = run_scene_file(o.drum_scene, sets, o.threads, o.seed, o.drum_repeats, sub_dir(o, name));
      if (o.progress) o.progress->scene_done(o.drum_scene, sets, m);
      nlohmann::json d = {{"dynamic_angle_of_repose_deg", sample_stats(per_run(m, "dynamic_angle_of_repose_deg"))},
                          {"cpu_seconds", m.value("cpu_seconds", 0.0)}, {"status", m.value("status", "ok")}};
      d["frames_sd_deg"] = sample_stats(per_run(m, "dynamic_angle_frames_sd_deg"))["samples"];
      return d;
    };
    const auto dhm = drum("hertz_mindlin", "drum_hm");
    const auto dnr = drum("hmnr", "drum_hmnr");
    const double x = mean_of(dhm["dynamic_angle_of_repose_deg"]), y = mean_of(dnr["dynamic_angle_of_repose_deg"]);
    j["drum"] = {{"scene", o.drum_scene}, {"hertz_mindlin", dhm}, {"hmnr", dnr},
                 {"angle_relative_difference", number_or_null((y - x) / x)},
                 {"paper", {{"hertz_mindlin_deg", 43.80}, {"hertz_mindlin_sd_deg", 7.46}, {"hmnr_deg", 43.75},
                            {"hmnr_sd_deg", 5.68}, {"note", "paper section 4, drum at 5 rpm, 188-sphere model"}}}};
  }
  return j;
}

nlohmann::json stiffness_study(const PaperStudyOptions& o) {
  nlohmann::json j = {{"study", "stiffness"}, {"free_drop_scene", o.free_drop_scene}, {"sets", o.sets},
                      {"repeats", o.repeats}, {"seed", o.seed}, {"rows", nlohmann::json::array()}};
  std::vector<double> points, heights;
  for (const double e : o.youngs_moduli_pa) {
    const std::string set = youngs_modulus_set(e);
    char name[64];
    std::snprintf(name, sizeof name, "free_drop_E%.3g", e);
    auto row = free_drop(o, with(o.sets, {"contact.model=hmnr", set}), name);
    row["youngs_modulus_pa"] = e;
    points.push_back(mean_of(row["contact_points"]));
    heights.push_back(mean_of(row["rebound_height_m"]));
    j["rows"].push_back(row);
  }
  // The paper's Figure 26: contact points fall and the rebound rises as E increases.
  // Over the moduli whose drops completed (a row stopped by a guard has no values).
  std::vector<double> p, h;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (std::isfinite(points[i]) && std::isfinite(heights[i])) {
      p.push_back(points[i]);
      h.push_back(heights[i]);
    }
  bool fall = p.size() >= 2, rise = p.size() >= 2;
  for (std::size_t i = 1; i < p.size(); ++i) {
    fall = fall && p[i] <= p[i - 1];
    rise = rise && h[i] >= h[i - 1];
  }
  j["rows_completed"] = p.size();
  j["contact_points_fall_with_E"] = fall;
  j["rebound_rises_with_E"] = rise;
  j["paper"] = "Figure 26: with HMNR, the number of contact points falls and the rebound height rises as E "
               "goes from 1.65e6 to 1.65e8 Pa (values not in the text)";
  return j;
}

nlohmann::json moisture_study(const std::string& variety) {
  const Variety v = read_variety(variety);
  const ModulusFit f = fit_modulus(v);
  auto line = [](const LineFit& l) {
    return nlohmann::json{{"model", l.model}, {"n", l.n}, {"c0", l.c0}, {"c1", l.c1}, {"r2", l.r2},
                          {"se_c1", l.se_c1}, {"t_c1", l.t_c1}, {"p_c1", l.p_c1}};
  };
  nlohmann::json j = {{"study", "moisture"}, {"variety", v.name}, {"file", v.file},
                      {"measured", {{"moisture_fraction", v.mc_moisture_fraction}, {"youngs_modulus_pa", v.mc_youngs_modulus_pa}}},
                      {"linear_fit", line(f.linear)}, {"log_linear_fit", line(f.log_linear)},
                      {"youngs_modulus_at_variety_moisture_pa", f.youngs_modulus_pa(v.moisture_fraction)},
                      {"variety_moisture_fraction", v.moisture_fraction}, {"rows", nlohmann::json::array()}};
  if (!f.flag.empty()) j["flag"] = f.flag;
  for (std::size_t i = 0; i < v.soak_hours.size(); ++i) {
    const Vec3 g = soaking_growth(v, v.soak_hours[i]);
    const Vec3& b = v.soak_before_m[i];
    const Vec3& a = v.soak_after_m[i];
    j["rows"].push_back({{"hours", v.soak_hours[i]},
                         {"before_m", {b.x(), b.y(), b.z()}},
                         {"after_m", {a.x(), a.y(), a.z()}},
                         {"growth_ratio", {g.x(), g.y(), g.z()}},
                         {"volume_growth_ratio", g.x() * g.y() * g.z()}});
  }
  j["note"] = "E(w) from the log-linear fit, ln E = c0 + c1 w (positive at every moisture); the modulus falls as "
              "moisture rises (paper section 4)";
  return j;
}

std::string study_csv(const nlohmann::json& s) {
  std::ostringstream out;
  out.precision(10);
  const std::string kind = s.value("study", "");
  auto cell = [](const nlohmann::json& x) { return x.is_number() ? x.dump() : std::string("n/a"); };
  if (kind == "multicontact") {
    out << "test,model,index,mean,sd,n\n";
    for (const char* m : {"hertz_mindlin", "hmnr"}) {
      const auto& fd = s["free_drop"][m];
      out << "free_drop," << m << ",rebound_height_m," << cell(fd["rebound_height_m"]["mean"]) << ","
          << cell(fd["rebound_height_m"]["sd"]) << "," << fd["rebound_height_m"]["n"] << "\n";
      out << "free_drop," << m << ",contact_points," << cell(fd["contact_points"]["mean"]) << ","
          << cell(fd["contact_points"]["sd"]) << "," << fd["contact_points"]["n"] << "\n";
      if (s.contains("drum")) {
        const auto& d = s["drum"][m]["dynamic_angle_of_repose_deg"];
        out << "drum," << m << ",dynamic_angle_of_repose_deg," << cell(d["mean"]) << "," << cell(d["sd"]) << ","
            << d["n"] << "\n";
      }
    }
  } else if (kind == "stiffness") {
    out << "youngs_modulus_pa,contact_points_mean,contact_points_sd,rebound_height_m_mean,rebound_height_m_sd,n\n";
    for (const auto& r : s["rows"])
      out << r["youngs_modulus_pa"].dump() << "," << cell(r["contact_points"]["mean"]) << ","
          << cell(r["contact_points"]["sd"]) << "," << cell(r["rebound_height_m"]["mean"]) << ","
          << cell(r["rebound_height_m"]["sd"]) << "," << r["rebound_height_m"]["n"] << "\n";
  } else if (kind == "moisture") {
    out << "hours,L_before_m,W_before_m,T_before_m,L_after_m,W_after_m,T_after_m,volume_growth_ratio\n";
    for (const auto& r : s["rows"])
      out << r["hours"].dump() << "," << r["before_m"][0].dump() << "," << r["before_m"][1].dump() << ","
          << r["before_m"][2].dump() << "," << r["after_m"][0].dump() << "," << r["after_m"][1].dump() << ","
          << r["after_m"][2].dump() << "," << r["volume_growth_ratio"].dump() << "\n";
  }
  return out.str();
}

}  // namespace seedcal
