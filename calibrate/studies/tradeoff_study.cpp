#include "calibrate/studies/tradeoff_study.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "calibrate/scenes/scene_file.hpp"
#include "calibrate/studies/study_stats.hpp"
#include "store/errors.hpp"

namespace seedcal {
namespace {


double num(const nlohmann::json& j, const char* key) {
  return j.contains(key) && j[key].is_number() ? j[key].get<double>() : kNaN;
}

// One row: the scene at `set` with every repeat, reduced to the index and the cost. A setting the
// scene refuses (a step above the stable limit) is a row with status "refused" and the message,
// except in the reference row (the first), where it is bad input: nothing could be compared.
nlohmann::json run_row(const TradeoffOptions& o, const std::string& set, const std::string& name, std::string& metric,
                       bool reference) {
  std::vector<std::string> sets = o.sets;
  if (!set.empty()) sets.push_back(set);
  nlohmann::json m;
  try {
    m = run_scene_file(o.scene, sets, o.threads, o.seed, o.repeats,
                       o.out_dir.empty() ? std::string() : o.out_dir + "/scenes/" + name, o.jobs);
  } catch (const InputError& e) {
    if (reference) throw;
    return {{"set", set}, {"index", sample_stats({})}, {"cpu_seconds_per_run", nullptr}, {"steps_per_run", nullptr},
            {"dt_s", nullptr}, {"seeds_per_run", nullptr}, {"spheres_per_run", nullptr}, {"status", "refused"},
            {"failure", {{"message", e.what()}}}};
  }
  if (o.progress) o.progress->scene_done(o.scene, sets, m);
  if (metric.empty()) metric = m.value("index_key", "");
  nlohmann::json row = {{"set", set}, {"index", sample_stats(per_run(m, metric))},
                        {"cpu_seconds_per_run", sample_stats(per_run(m, "cpu_seconds"))["mean"]},
                        {"steps_per_run", sample_stats(per_run(m, "steps"))["mean"]},
                        {"dt_s", sample_stats(per_run(m, "dt_s"))["mean"]},
                        // The rig's size: seeds (bodies) and spheres at the end of a run.
                        {"seeds_per_run", sample_stats(per_run(m, "bodies"))["mean"]},
                        {"spheres_per_run", sample_stats(per_run(m, "spheres"))["mean"]},
                        {"status", m.value("status", "ok")}};
  if (m.contains("failure")) row["failure"] = m["failure"];
  return row;
}

// Change of every row against the reference row, its significance (|difference| above two
// pooled standard errors, sqrt(sd_a^2/n_a + sd_b^2/n_b): the same seeds in both rows make this
// conservative) and the speed-up; then the cheapest row within the tolerance.
void compare(nlohmann::json& sweep, std::size_t reference, double tolerance) {
  auto& rows = sweep["rows"];
  const auto& ref = rows[reference];
  const double y0 = mean_of(ref["index"]), cpu0 = num(ref, "cpu_seconds_per_run");
  const double sd0 = num(ref["index"], "sd");
  const double n0 = ref["index"]["n"].get<double>();
  double best_speedup = 0.0;
  nlohmann::json cheapest = nullptr;
  for (auto& r : rows) {
    const double y = mean_of(r["index"]), cpu = num(r, "cpu_seconds_per_run");
    const double sd = num(r["index"], "sd"), n = r["index"]["n"].get<double>();
    const double change = (y - y0) / y0;
    const double se = std::sqrt((std::isfinite(sd) ? sd * sd / n : 0.0) + (std::isfinite(sd0) ? sd0 * sd0 / n0 : 0.0));
    r["relative_change"] = number_or_null(change);
    r["significant"] = std::isfinite(change) && se > 0.0 ? nlohmann::json(std::fabs(y - y0) > 2.0 * se) : nlohmann::json(nullptr);
    r["speedup"] = number_or_null(cpu0 / cpu);
    r["within_tolerance"] = std::isfinite(change) && std::fabs(change) <= tolerance;
    if (r["within_tolerance"].get<bool>() && std::isfinite(cpu0 / cpu) && cpu0 / cpu > best_speedup) {
      best_speedup = cpu0 / cpu;
      cheapest = r["value"];
    }
  }
  sweep["reference"] = ref["value"];
  sweep["cheapest_within_tolerance"] = cheapest;
}

}  // namespace

namespace {

std::string fraction_set(double f) {
  char set[64];
  std::snprintf(set, sizeof set, "rayleigh_fraction=%.17g", f);
  return set;
}

std::string modulus_set(const std::string& material, double e) {
  char set[128];
  std::snprintf(set, sizeof set, "materials.%s.youngs_modulus_pa=%.17g", material.c_str(), e);
  return set;
}

}  // namespace

namespace {

// The scene's own step fraction and modulus, read from the scene as it stands (overrides
// applied): they decide whether the modulus sweep's reference row is a row the step sweep has
// already run. Throws InputError for a scene the sweeps cannot vary.
struct SweepScene {
  double own_modulus = 0.0, own_fraction = 0.2;
};

SweepScene check_sweep_scene(const TradeoffOptions& o) {
  const SceneFile scene = load_scene_file(o.scene, o.sets);
  if (scene.doc.contains("dt_s"))
    throw InputError(o.scene + ": dt_s is set: the step-fraction sweep needs a scene whose step comes from "
                     "rayleigh_fraction (remove dt_s)");
  const toml::value* modulus = nullptr;
  if (scene.doc.contains("materials") && scene.doc.at("materials").contains(o.material) &&
      scene.doc.at("materials").at(o.material).contains("youngs_modulus_pa"))
    modulus = &scene.doc.at("materials").at(o.material).at("youngs_modulus_pa");
  if (!modulus || !(modulus->is_floating() || modulus->is_integer()))
    throw InputError(o.scene + ": --material " + o.material + ": the scene has no materials." + o.material +
                     ".youngs_modulus_pa to sweep");
  auto number = [](const toml::value& v) { return v.is_floating() ? v.as_floating() : static_cast<double>(v.as_integer()); };
  SweepScene s;
  s.own_modulus = number(*modulus);
  if (scene.doc.contains("rayleigh_fraction")) s.own_fraction = number(scene.doc.at("rayleigh_fraction"));
  return s;
}

// The sweeps in the order they run: step fractions rising, moduli falling (stiffest first).
std::vector<double> fractions_in_order(const TradeoffOptions& o) {
  std::vector<double> f = o.rayleigh_fractions;
  std::sort(f.begin(), f.end());
  return f;
}
std::vector<double> moduli_in_order(const TradeoffOptions& o) {
  std::vector<double> m = o.youngs_moduli_pa;
  std::sort(m.rbegin(), m.rend());
  return m;
}

}  // namespace

std::vector<PlannedRuns> tradeoff_plan(const TradeoffOptions& o) {
  const SweepScene scene = check_sweep_scene(o);
  std::vector<PlannedRuns> plan;
  // The first row of each sweep is its reference: a setting refused there is bad input; a later
  // one is recorded as refused (run_row).
  auto row = [&](const std::string& set, bool reference) {
    std::vector<std::string> sets = o.sets;
    sets.push_back(set);
    plan.push_back({set, o.scene, sets, o.repeats, !reference});
  };
  const std::vector<double> fractions = fractions_in_order(o), moduli = moduli_in_order(o);
  for (std::size_t i = 0; i < fractions.size(); ++i) row(fraction_set(fractions[i]), i == 0);
  const bool own_fraction_runs =
      std::find(fractions.begin(), fractions.end(), scene.own_fraction) != fractions.end();
  for (std::size_t i = 0; i < moduli.size(); ++i) {
    // The scene's own modulus at its own step is a row of the step sweep already: not run again.
    if (own_fraction_runs && moduli[i] == scene.own_modulus) continue;
    row(modulus_set(o.material, moduli[i]), i == 0);
  }
  return plan;
}

nlohmann::json tradeoff_study(const TradeoffOptions& o) {
  const SweepScene scene = check_sweep_scene(o);
  const double own_modulus = scene.own_modulus, own_fraction = scene.own_fraction;

  std::string metric = o.metric;
  nlohmann::json j = {{"study", "tradeoff"}, {"scene", o.scene}, {"sets", o.sets}, {"repeats", o.repeats},
                      {"seed", o.seed}, {"tolerance", o.tolerance}};
  nlohmann::json dt = {{"parameter", "rayleigh_fraction"}, {"rows", nlohmann::json::array()}};
  for (const double f : fractions_in_order(o)) {
    const std::string set = fraction_set(f);
    char name[64];
    std::snprintf(name, sizeof name, "rayleigh_fraction_%.3g", f);
    auto row = run_row(o, set, name, metric, dt["rows"].empty());
    row["value"] = f;
    dt["rows"].push_back(row);
  }
  nlohmann::json stiff = {{"parameter", "materials." + o.material + ".youngs_modulus_pa"},
                          {"rows", nlohmann::json::array()}};
  for (const double e : moduli_in_order(o)) {
    const std::string set = modulus_set(o.material, e);
    char name[64];
    std::snprintf(name, sizeof name, "youngs_modulus_%.3g", e);
    nlohmann::json row;
    const nlohmann::json* same = nullptr;  // the step sweep's row at the scene's own step and modulus
    if (e == own_modulus)
      for (const auto& r : dt["rows"])
        if (r["value"].get<double>() == own_fraction && r["status"] == "ok") same = &r;
    if (same) {
      row = *same;
      row["set"] = set;
      row["same_runs_as"] = "rayleigh_fraction = " + (*same)["value"].dump();
    } else {
      row = run_row(o, set, name, metric, stiff["rows"].empty());
    }
    row["value"] = e;
    stiff["rows"].push_back(row);
  }
  if (!dt["rows"].empty()) compare(dt, 0, o.tolerance);
  if (!stiff["rows"].empty()) compare(stiff, 0, o.tolerance);
  j["metric"] = metric;
  j["sweeps"] = {dt, stiff};
  return j;
}

std::string tradeoff_csv(const nlohmann::json& s) {
  std::ostringstream out;
  out.precision(10);
  auto cell = [](const nlohmann::json& x) { return x.is_number() ? x.dump() : std::string("n/a"); };
  out << "parameter,value,index_mean,index_sd,n,relative_change,significant,cpu_seconds_per_run,steps_per_run,"
         "seeds_per_run,spheres_per_run,speedup,within_tolerance,status\n";
  for (const auto& sw : s["sweeps"])
    for (const auto& r : sw["rows"])
      out << sw["parameter"].get<std::string>() << "," << cell(r["value"]) << "," << cell(r["index"]["mean"]) << ","
          << cell(r["index"]["sd"]) << "," << r["index"]["n"] << "," << cell(r["relative_change"]) << ","
          << (r["significant"].is_boolean() ? (r["significant"].get<bool>() ? "yes" : "no") : "n/a") << ","
          << cell(r["cpu_seconds_per_run"]) << "," << cell(r["steps_per_run"]) << ","
          << cell(r["seeds_per_run"]) << "," << cell(r["spheres_per_run"]) << "," << cell(r["speedup"]) << ","
          << (r["within_tolerance"].get<bool>() ? "yes" : "no") << "," << r["status"].get<std::string>() << "\n";
  return out.str();
}

}  // namespace seedcal
