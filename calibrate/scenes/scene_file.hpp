#pragma once
// Runs a scene file in this process: read, take the seed's values from the variety it names
// (variety_scene.hpp; a `--set variety=...` first), apply overrides (--set paths), check `kind` (with a
// suggestion for a misspelt one) and `repeats`, run the seeds through the scene registry and
// return the aggregated metrics (scene_registry.hpp, run_repeated). A bad config throws
// InputError; a failed simulation comes back with status != "ok".
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <toml.hpp>

#include "calibrate/config/variety_scene.hpp"
#include "calibrate/scenes/scene_registry.hpp"

namespace seedcal {

// A scene file read and checked, overrides applied: ready to run.
struct SceneFile {
  std::string path;
  toml::value doc;        // the effective config
  std::string kind;
  const SceneRunner* runner = nullptr;
  int repeats = 1;        // the file's `repeats` key
  VarietyDefaults variety;  // what the variety it names supplied (variety_scene.hpp)
};

SceneFile load_scene_file(const std::string& path, const std::vector<std::string>& sets);

// Reads every key of the scene as a run would ([output] and `repeats` included) and throws
// InputError naming the file, key, value and range for the first bad one; runs nothing. Returns
// the config's warnings (what a run would say under "warnings").
std::vector<std::string> check_scene(const SceneFile& scene);

// What one run of the scene would simulate (run_plan.hpp), worked out from its config; runs
// nothing. Throws as check_scene does.
RunPlan plan_scene(const SceneFile& scene);

// Runs `repeats` seeds (seed, seed + 1, ...), `jobs` at a time; repeats = 0: the file's own
// `repeats`. `progress` (optional) is called as SceneContext::progress says.
nlohmann::json run_scene(const SceneFile& scene, int threads, std::uint64_t seed, int repeats,
                         const std::string& out_dir = "", int jobs = 1,
                         const std::function<void(std::size_t run, const Simulation& sim)>& progress = {});

nlohmann::json run_scene_file(const std::string& path, const std::vector<std::string>& sets, int threads,
                              std::uint64_t seed, int repeats, const std::string& out_dir = "", int jobs = 1);

}  // namespace seedcal
