#include "calibrate/scenes/scene_registry.hpp"

#include <cmath>

namespace seedcal {

const std::map<std::string, SceneRunner>& scene_registry() {
  static const std::map<std::string, SceneRunner> kScenes = {
      {"impact", run_impact_scene},
      {"free_drop", run_free_drop_scene},
      {"bulk_density", run_bulk_density_scene},
      {"direct_shear", run_direct_shear_scene},
      {"piling", run_piling_scene},
      {"drum", run_drum_scene},
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
  if (r.failure.status != RunStatus::ok) {
    j["failure"] = {{"step", r.failure.step},
                    {"time_s", r.failure.time_s},
                    {"body", r.failure.body},
                    {"message", r.failure.message}};
  }
}

}  // namespace seedcal

namespace seedcal {

nlohmann::json run_repeated(const SceneRunner& runner, const toml::value& doc,
                            const std::string& config_path, const SceneContext& ctx, int repeats) {
  std::vector<nlohmann::json> runs;
  for (int k = 0; k < repeats; ++k) {
    auto diag = std::make_shared<ConfigDiagnostics>();
    diag->file = config_path;
    TomlReader root(doc, "", diag);
    root.integer("repeats", 1, 1000, 1);
    SceneContext c = ctx;
    c.seed = ctx.seed + static_cast<std::uint64_t>(k);
    runs.push_back(runner(root, c));
    runs.back()["seed"] = c.seed;
    if (runs.back().value("status", "ok") != "ok") break;  // a failed run ends the series
  }
  nlohmann::json out = runs.front();
  const std::string key = out.value("index_key", "");
  if (!key.empty()) {
    std::vector<double> xs;
    for (const auto& r : runs)
      if (r.contains(key) && r[key].is_number()) xs.push_back(r[key].get<double>());
    double mean = 0.0, var = 0.0;
    for (double x : xs) mean += x;
    mean /= static_cast<double>(std::max<std::size_t>(1, xs.size()));
    for (double x : xs) var += (x - mean) * (x - mean);
    out[key] = mean;
    out[key + "_sd"] = xs.size() > 1 ? std::sqrt(var / static_cast<double>(xs.size() - 1)) : 0.0;
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
  out["wall_seconds"] = wall;
  out["steps"] = steps;
  out["repeats"] = runs.size();
  if (runs.size() > 1) out["runs"] = runs;
  out.erase("seed");
  return out;
}

}  // namespace seedcal
