#include "calibrate/scenes/scene_registry.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <optional>
#include <string>
#include <vector>

#include <gsl/gsl_statistics_double.h>

#include "calibrate/config/output_config.hpp"
#include "calibrate/output/trajectory_h5.hpp"
#include "calibrate/scenes/job_pool.hpp"
#include "store/version.hpp"

namespace seedcal {

const std::map<std::string, SceneRunner>& scene_registry() {
  static const std::map<std::string, SceneRunner> kScenes = {
      {"impact", run_impact_scene},
      {"free_drop", run_free_drop_scene},
      {"bulk_density", run_bulk_density_scene},
      {"direct_shear", run_direct_shear_scene},
      {"piling", run_piling_scene},
      {"drum", run_drum_scene},
      {"custom", run_custom_scene},
  };
  return kScenes;
}

void add_run_report(nlohmann::json& j, const RunReport& r) {
  j["cpu_seconds"] = r.cpu_seconds;
  j["wall_seconds"] = r.wall_seconds;
  j["steps"] = r.steps;
  j["bodies"] = r.bodies;
  j["spheres"] = r.spheres;
  j["dt_s"] = r.dt_s;
  j["stop_reason"] = r.stop_reason;
  j["status"] = to_string(r.failure.status);
  j["deepest_overlap_fraction"] = r.deepest_overlap_fraction;
  j["phases"] = nlohmann::json::array();
  for (const PhaseRecord& p : r.phases)
    j["phases"].push_back(
        {{"name", p.name}, {"simulated_s", p.simulated_s}, {"steps", p.steps}, {"cpu_seconds", p.cpu_seconds}});
  if (r.failure.status != RunStatus::ok) {
    j["failure"] = {{"step", r.failure.step},
                    {"time_s", r.failure.time_s},
                    {"body", r.failure.body},
                    {"message", r.failure.message}};
  }
}

}  // namespace seedcal

namespace seedcal {
namespace {

// Removes every non-finite number from a run's metrics (a run a guard stopped may end with NaN
// positions): an array holding one loses the whole array, an object the key. The removed paths
// are listed under "non_finite_removed", so no NaN (written as null by nlohmann::json) reaches
// metrics.json or the study store, and nothing is silently lost.
bool finite_or_remove(nlohmann::json& j, const std::string& path, std::vector<std::string>& removed) {
  if (j.is_number_float()) return std::isfinite(j.get<double>());
  if (j.is_array()) {
    for (std::size_t i = 0; i < j.size(); ++i)
      if (!finite_or_remove(j[i], path + "[" + std::to_string(i) + "]", removed)) return false;
    return true;
  }
  if (j.is_object()) {
    std::vector<std::string> bad;
    for (auto& [k, v] : j.items())
      if (!finite_or_remove(v, path.empty() ? k : path + "." + k, removed)) bad.push_back(k);
    for (const std::string& k : bad) {
      j.erase(k);
      removed.push_back(path.empty() ? k : path + "." + k);
    }
  }
  return true;
}

void remove_non_finite(nlohmann::json& j) {
  std::vector<std::string> removed;
  finite_or_remove(j, "", removed);
  if (!removed.empty()) j["non_finite_removed"] = removed;
}

}  // namespace

namespace {

// Run k of a series: seed ctx.seed + k, a fresh read of the config.
nlohmann::json run_one(const SceneRunner& runner, const toml::value& doc, const std::string& config_path,
                       const SceneContext& ctx, std::size_t k) {
  auto diag = std::make_shared<ConfigDiagnostics>();
  diag->file = config_path;
  TomlReader root(doc, "", diag);
  root.integer("repeats", 1, 1000, 1);
  const OutputConfig output = read_output(root);
  SceneContext c = ctx;
  c.seed = ctx.seed + static_cast<std::uint64_t>(k);
  // The scene's files (its CSV, picture and trajectory) come from the first run, the one whose
  // seed the provenance names; the later runs only add their index to the statistics.
  if (k > 0) c.out_dir.clear();
  // The trajectory of the first run (its seed is the one metrics.json's provenance names). The
  // writer finishes (writes the XDMF) when it goes out of scope, also when the runner throws.
  std::optional<TrajectoryWriter> trajectory;
  if (output.trajectory && k == 0 && !ctx.out_dir.empty()) {
    const std::string kind =
        doc.contains("kind") && doc.at("kind").is_string() ? doc.at("kind").as_string().str : "";
    trajectory.emplace(ctx.out_dir,
                       TrajectoryProvenance{version_string(), kind, config_path, toml::format(doc),
                                            c.seed, ctx.threads},
                       output.trajectory_interval_s);
    c.observer = trajectory->observer();
  }
  if (ctx.progress) {
    c.observer.progress_interval_s = ctx.progress_interval_s;
    c.observer.on_progress = [&ctx, k](const Simulation& sim) { ctx.progress(k, sim); };
  }
  // What the run was planned to simulate (run_plan.hpp), beside what it did: the runner states it
  // from the spec it has read, before it simulates.
  RunPlan plan;
  if (!ctx.check_only) c.plan = &plan;
  nlohmann::json run = runner(root, c);
  if (!ctx.check_only) {
    run["plan"] = {{"simulated_s", plan.simulated_s()}, {"steps", plan.steps()}, {"seeds", plan.seeds},
                   {"spheres", plan.spheres}, {"sphere_steps", plan.sphere_steps()}};
    run["plan"]["phases"] = nlohmann::json::array();
    for (const PlanPhase& p : plan.phases)
      run["plan"]["phases"].push_back({{"name", p.name}, {"simulated_s", p.simulated_s}, {"spheres", p.spheres}});
  }
  // The config's warnings (a clump with a buried sphere) beside the scene's own.
  for (const std::string& w : diag->warnings) run["warnings"].push_back(w);
  if (trajectory) {
    trajectory->finish();
    run["trajectory"] = {{"h5", TrajectoryWriter::kH5Name},
                         {"xdmf", TrajectoryWriter::kXdmfName},
                         {"frames", trajectory->frames()},
                         {"interval_s", trajectory->interval_s()}};
  }
  remove_non_finite(run);
  run["seed"] = c.seed;
  return run;
}

}  // namespace

nlohmann::json run_repeated(const SceneRunner& runner, const toml::value& doc,
                            const std::string& config_path, const SceneContext& ctx, int repeats) {
  const auto n = static_cast<std::size_t>(std::max(repeats, 1));
  const auto t0 = std::chrono::steady_clock::now();
  // A failed run (or one that throws) ends the series: the runs after it are not started, and
  // those already under way when it fails are dropped below, so that `jobs` runs at a time give
  // the series of one job.
  std::vector<nlohmann::json> all(n);
  std::atomic<std::size_t> first_failed{n};
  const std::vector<std::exception_ptr> errors = run_jobs(n, ctx.jobs, [&](std::size_t k) {
    if (k > first_failed.load()) return;
    try {
      all[k] = run_one(runner, doc, config_path, ctx, k);
    } catch (...) {
      lower_to(first_failed, k);
      throw;
    }
    if (all[k].value("status", "ok") != "ok") lower_to(first_failed, k);
  });
  std::vector<nlohmann::json> runs;
  for (std::size_t k = 0; k < n; ++k) {
    if (errors[k]) std::rethrow_exception(errors[k]);
    runs.push_back(std::move(all[k]));
    if (runs.back().value("status", "ok") != "ok") break;
  }
  const double elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  nlohmann::json out = runs.front();
  const std::string key = out.value("index_key", "");
  if (!key.empty()) {
    std::vector<double> xs;
    for (const auto& r : runs)
      if (r.contains(key) && r[key].is_number()) xs.push_back(r[key].get<double>());
    // Mean and sample sd (n - 1) by GSL; one run has sd 0.
    const double mean = xs.empty() ? 0.0 : gsl_stats_mean(xs.data(), 1, xs.size());
    out[key] = mean;
    out[key + "_sd"] = xs.size() > 1 ? gsl_stats_sd_m(xs.data(), 1, xs.size(), mean) : 0.0;
    out[key + "_samples"] = xs;
  }
  double cpu = 0.0, wall = 0.0;
  std::uint64_t steps = 0;
  for (const auto& r : runs) {
    cpu += r.value("cpu_seconds", 0.0);
    wall += r.value("wall_seconds", 0.0);
    steps += r.value("steps", std::uint64_t{0});
    if (r.value("status", "ok") != "ok") {
      out["status"] = r["status"];
      out["failure"] = r.value("failure", nlohmann::json::object());
      out["stop_reason"] = r["stop_reason"];
    }
  }
  out["cpu_seconds"] = cpu;
  // One run: its own wall time. A series: from the first run's start to the last run's end, which
  // is less than the runs' sum when they ran side by side (each run keeps its own under "runs").
  out["wall_seconds"] = runs.size() == 1 ? wall : elapsed_s;
  out["steps"] = steps;
  out["repeats"] = runs.size();
  out["jobs"] = std::min<std::size_t>(static_cast<std::size_t>(std::max(ctx.jobs, 1)), n);
  if (runs.size() > 1) {
    out["runs"] = runs;
    out["files_from_seed"] = ctx.seed;
  }
  out.erase("seed");
  return out;
}

}  // namespace seedcal
