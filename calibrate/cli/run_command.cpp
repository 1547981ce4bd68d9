// `seedcal run SCENE.toml --out DIR [--set key=value ...]`: one virtual test.
#include <chrono>
#include <ctime>
#include <filesystem>
#include <iostream>

#include "calibrate/cli/commands.hpp"
#include "calibrate/cli/errors.hpp"
#include "calibrate/config/overrides.hpp"
#include "calibrate/config/toml_reader.hpp"
#include "calibrate/io/atomic_file.hpp"
#include "calibrate/scenes/scene_registry.hpp"
#include "solver/core/errors.hpp"

namespace seedcal {
namespace {

struct RunArgs {
  std::string scene;
  std::string out = "out";
  std::vector<std::string> sets;
};

std::vector<std::string> kinds() {
  std::vector<std::string> k;
  for (const auto& [name, _] : scene_registry()) k.push_back(name);
  return k;
}

void run_scene(const RunArgs& a, const GlobalOptions& g) {
  toml::value doc = TomlReader::parse_file(a.scene);
  apply_overrides(doc, a.sets);
  auto diag = std::make_shared<ConfigDiagnostics>();
  diag->file = a.scene;
  TomlReader root(doc, "", diag);
  const std::string kind = root.has("kind") && doc.at("kind").is_string()
                               ? doc.at("kind").as_string().str : std::string();
  const auto& reg = scene_registry();
  const auto it = reg.find(kind);
  if (it == reg.end()) {
    root.choice("kind", kinds());
    if (!root.has("kind")) root.error("kind", "is required");
    diag->throw_if_any();
    throw InputError(a.scene + ": kind = \"" + kind + "\": unknown scene kind");
  }
  SceneContext ctx{a.scene, a.out, g.resolved_threads(), g.seed};
  const int repeats = static_cast<int>(root.integer("repeats", 1, 1000, 1));
  diag->throw_if_any();
  nlohmann::json metrics;
  try {
    metrics = run_repeated(it->second, doc, a.scene, ctx, repeats);
  } catch (const SettingError& e) {
    throw InputError(a.scene + ": " + e.what());
  }
  metrics["scene"] = kind;
  metrics["provenance"] = {{"seedcal_version", version_string()},
                           {"config_file", a.scene},
                           {"overrides", a.sets},
                           {"seed", g.seed},
                           {"threads", ctx.threads},
                           {"config", toml::format(doc)}};
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
  sub->callback([args, &g] { run_scene(*args, g); });
}

}  // namespace seedcal
