// `seedcal run SCENE.toml --out DIR [--set key=value ...]`: one virtual test.
#include <algorithm>
#include <chrono>
#include <ctime>
#include <filesystem>
#include <iostream>

#include <unistd.h>

#include "app/commands.hpp"
#include "calibrate/output/run_progress_line.hpp"
#include "calibrate/scenes/scene_file.hpp"
#include "store/atomic_file.hpp"
#include "store/errors.hpp"

namespace seedcal {
namespace {

struct RunArgs {
  std::string scene;
  std::string out = "out";
  std::vector<std::string> sets;
  int jobs = 1;
  bool quiet = false;
};

void run_scene_command(const RunArgs& a, const GlobalOptions& g) {
  const SceneFile scene = load_scene_file(a.scene, a.sets);
  // The config's warnings before the run (they are in metrics.json too).
  for (const std::string& w : check_scene(scene)) std::cerr << "seedcal: warning: " << w << "\n";
  // More jobs than repeats would idle.
  const int jobs = std::min(a.jobs, scene.repeats);
  const int threads = g.threads_per_job(jobs);
  // A status line on a terminal (the plan gives the simulated time a run will take).
  const bool line_on = !a.quiet && ::isatty(STDERR_FILENO);
  RunProgressLine line(line_on ? plan_scene(scene) : RunPlan{}, scene.repeats, jobs, line_on);
  nlohmann::json metrics =
      run_scene(scene, threads, g.seed, 0, a.out, jobs,
                line_on ? [&line](std::size_t k, const Simulation& sim) { line.update(k, sim); }
                        : std::function<void(std::size_t, const Simulation&)>{});
  line.clear();
  metrics["scene"] = scene.kind;
  metrics["provenance"] = {{"seedcal_version", version_string()},
                           {"config_file", a.scene},
                           {"overrides", a.sets},
                           {"seed", g.seed},
                           {"threads", threads},
                           {"jobs", jobs},
                           {"config", toml::format(scene.doc)}};
  std::filesystem::create_directories(a.out);
  write_json_atomic(a.out + "/metrics.json", metrics);
  std::cout << metrics.dump(2) << "\n";
  if (metrics.value("status", "ok") != "ok") {
    const std::string msg = metrics.contains("failure") ? metrics["failure"].value("message", "") : "";
    throw RunFailed(a.scene + ": the simulation stopped: " + msg);
  }
}

}  // namespace

void add_run_command(CLI::App& app, GlobalOptions& g) {
  auto args = std::make_shared<RunArgs>();
  CLI::App* sub = app.add_subcommand("run", "run one virtual test (scene) and write DIR/metrics.json");
  sub->add_option("scene", args->scene, "scene config (TOML)")->required();
  sub->add_option("--out", args->out, "output directory (default: out)");
  sub->add_option("--set", args->sets, "override a config value: key=value (dotted TOML path)");
  sub->add_option("--jobs", args->jobs,
                  "repeats run at once, one thread each (default 1); the same results as one at a time")
      ->check(CLI::Range(1, 1024));
  sub->add_flag("--quiet", args->quiet, "no progress line on the terminal");
  add_common_options(*sub, g);
  sub->callback([args, &g] { run_scene_command(*args, g); });
}

}  // namespace seedcal
