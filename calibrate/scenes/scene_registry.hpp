#pragma once
// The table of scene kinds `seedcal run` knows, each a function that reads its config, runs, and
// returns its metrics (the index under its stable key plus the run report).
#include <cstdint>
#include <functional>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "calibrate/config/toml_reader.hpp"
#include "solver/scenes/run_plan.hpp"
#include "solver/scenes/scene_common.hpp"

namespace seedcal {

struct SceneContext {
  std::string config_path;
  std::string out_dir;  // where the scene may write extra files (CSV, pictures); may be empty
  int threads = 1;
  std::uint64_t seed = 0;
  FrameObserver observer;  // the run's frames ([output] trajectory = true); runners pass it on
  bool check_only = false;  // read and validate the whole config, then return without running
  RunPlan* plan = nullptr;  // with check_only: set to what a run would simulate (run_plan.hpp)
  // Progress of each run (optional, a status line): called with the run's index in the series and
  // its simulation every progress_interval_s of simulated time, from the thread that runs it.
  std::function<void(std::size_t run, const Simulation& sim)> progress;
  double progress_interval_s = 1e-3;
  int jobs = 1;             // run_repeated: runs at once (each with `threads` threads)
};

using SceneRunner = std::function<nlohmann::json(TomlReader& root, const SceneContext& ctx)>;

const std::map<std::string, SceneRunner>& scene_registry();

// Runs a scene `repeats` times with seeds seed, seed + 1, ... (a fresh config read each time),
// ctx.jobs runs at a time (calibrate/scenes/job_pool.hpp; the same results as one at a time), and
// aggregates: the index (named by the runner's "index_key") becomes the mean, with
// "<index>_sd" (sample standard deviation) and "<index>_samples"; cpu_seconds, wall_seconds and
// steps are summed (wall_seconds: the series' elapsed time, the runs' sum when they ran one at a
// time); every run's own metrics are kept under "runs". It reads the [output] table:
// with ctx.out_dir set, `trajectory = true` records the first run's trajectory there
// (output/trajectory_h5.hpp) and its metrics gain "trajectory" (files, frames, interval).
nlohmann::json run_repeated(const SceneRunner& runner, const toml::value& doc,
                            const std::string& config_path, const SceneContext& ctx, int repeats);


// The run-report part of every metrics object.
void add_run_report(nlohmann::json& j, const RunReport& r);

// Scene runners (one file each).
nlohmann::json run_impact_scene(TomlReader& root, const SceneContext& ctx);
nlohmann::json run_free_drop_scene(TomlReader& root, const SceneContext& ctx);
nlohmann::json run_bulk_density_scene(TomlReader& root, const SceneContext& ctx);
nlohmann::json run_direct_shear_scene(TomlReader& root, const SceneContext& ctx);
nlohmann::json run_piling_scene(TomlReader& root, const SceneContext& ctx);
nlohmann::json run_drum_scene(TomlReader& root, const SceneContext& ctx);
nlohmann::json run_custom_scene(TomlReader& root, const SceneContext& ctx);

}  // namespace seedcal
