// `seedcal run SCENE.toml --out DIR [--set key=value ...]`: one virtual test.
#include <chrono>
#include <ctime>
#include <filesystem>
#include <iostream>

#include "calibrate/cli/commands.hpp"
#include "calibrate/cli/errors.hpp"
#include "calibrate/io/atomic_file.hpp"
#include "calibrate/scenes/scene_file.hpp"

namespace seedcal {
namespace {

struct RunArgs {
  std::string scene;
  std::string out = "out";
  std::vector<std::string> sets;
};

void run_scene_command(const RunArgs& a, const GlobalOptions& g) {
  const SceneFile scene = load_scene_file(a.scene, a.sets);
  const int threads = g.resolved_threads();
  nlohmann::json metrics = run_scene(scene, threads, g.seed, 0, a.out);
  metrics["scene"] = scene.kind;
  metrics["provenance"] = {{"seedcal_version", version_string()},
                           {"config_file", a.scene},
                           {"overrides", a.sets},
                           {"seed", g.seed},
                           {"threads", threads},
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
  add_common_options(*sub, g);
  sub->callback([args, &g] { run_scene_command(*args, g); });
}

}  // namespace seedcal
