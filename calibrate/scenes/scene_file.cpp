#include "calibrate/scenes/scene_file.hpp"

#include <filesystem>

#include "calibrate/config/overrides.hpp"
#include "calibrate/config/toml_reader.hpp"
#include "solver/core/errors.hpp"
#include "store/errors.hpp"

namespace seedcal {

SceneFile load_scene_file(const std::string& path, const std::vector<std::string>& sets) {
  SceneFile f;
  f.path = path;
  f.doc = TomlReader::parse_file(path);
  // The variety first (a --set may name another one), then its values, then every override, so
  // that a --set of a value the variety supplied wins.
  std::vector<std::string> variety_sets;
  for (const std::string& s : sets)
    if (s.rfind("variety=", 0) == 0) variety_sets.push_back(s);
  apply_overrides(f.doc, variety_sets);
  f.variety = apply_variety(f.doc, path);
  apply_overrides(f.doc, sets);
  auto diag = std::make_shared<ConfigDiagnostics>();
  diag->file = path;
  TomlReader root(f.doc, "", diag);
  f.kind = f.doc.contains("kind") && f.doc.at("kind").is_string() ? f.doc.at("kind").as_string().str : "";
  const auto& reg = scene_registry();
  const auto it = reg.find(f.kind);
  if (it == reg.end()) {
    std::vector<std::string> kinds;
    for (const auto& [name, _] : reg) kinds.push_back(name);
    root.choice("kind", kinds);  // names the allowed kinds and the closest one
    if (!root.has("kind")) root.error("kind", "is required");
    diag->throw_if_any();
    throw InputError(path + ": kind = \"" + f.kind + "\": unknown scene kind");
  }
  f.runner = &it->second;
  f.repeats = static_cast<int>(root.integer("repeats", 1, 1000, 1));
  diag->throw_if_any();
  return f;
}

namespace {

// A scene's runs through run_repeated (which reads `repeats` and [output] as well), a setting the
// solver refuses reported as bad input naming the file.
nlohmann::json run_with(const SceneFile& f, const SceneContext& ctx, int repeats) {
  try {
    nlohmann::json j = run_repeated(*f.runner, f.doc, f.path, ctx, repeats);
    for (const std::string& r : f.variety.replaced) j["warnings"].push_back(f.path + ": " + r);
    if (!f.variety.variety_file.empty()) j["variety"] = f.variety.variety_file;
    return j;
  } catch (const SettingError& e) {
    throw InputError(f.path + ": " + e.what());
  }
}

}  // namespace

std::vector<std::string> check_scene(const SceneFile& f) {
  SceneContext ctx;
  ctx.config_path = f.path;
  ctx.check_only = true;  // the runner reads its whole config and returns before simulating
  const nlohmann::json j = run_with(f, ctx, 1);
  return j.value("warnings", std::vector<std::string>{});
}

RunPlan plan_scene(const SceneFile& f) {
  SceneContext ctx;
  ctx.config_path = f.path;
  ctx.check_only = true;
  RunPlan plan;
  ctx.plan = &plan;
  run_with(f, ctx, 1);
  return plan;
}

nlohmann::json run_scene(const SceneFile& f, int threads, std::uint64_t seed, int repeats, const std::string& out_dir,
                         int jobs, const std::function<void(std::size_t run, const Simulation& sim)>& progress) {
  if (!out_dir.empty()) std::filesystem::create_directories(out_dir);
  SceneContext ctx;
  ctx.config_path = f.path;
  ctx.out_dir = out_dir;
  ctx.threads = threads;
  ctx.seed = seed;
  ctx.jobs = jobs;
  ctx.progress = progress;
  return run_with(f, ctx, repeats > 0 ? repeats : f.repeats);
}

nlohmann::json run_scene_file(const std::string& path, const std::vector<std::string>& sets, int threads,
                              std::uint64_t seed, int repeats, const std::string& out_dir, int jobs) {
  return run_scene(load_scene_file(path, sets), threads, seed, repeats, out_dir, jobs);
}

}  // namespace seedcal
