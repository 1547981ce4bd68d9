// `seedcal keys [KIND] [--markdown]`: what a scene kind's rig table accepts (key, unit, meaning,
// range, default) and what its metrics.json holds, from the scene's own schema declaration
// (calibrate/scenes/scene_schema.hpp). Without KIND: the scene kinds and the run report's metrics
// every scene writes. --markdown prints the tables of docs/scenes/KIND.md (scripts/scene_keys.sh
// checks the committed docs against them).
#include <iostream>
#include <memory>
#include <string>

#include "app/commands.hpp"
#include "calibrate/scenes/scene_schema.hpp"
#include "store/errors.hpp"

namespace seedcal {
namespace {

void print_text(const SchemaTable& t) {
  std::cout << "scene " << t.kind << ": keys of " << t.table << "\n";
  for (const SchemaKey& k : t.keys)
    std::cout << "  " << k.key << (k.unit.empty() ? "" : " [" + k.unit + "]") << "  " << k.range << "  default "
              << k.default_text << "\n      " << k.meaning << "\n";
  std::cout << "metrics (metrics.json) besides the run report's:\n";
  for (const SchemaMetric& m : t.metrics)
    std::cout << "  " << m.key << (m.unit.empty() ? "" : " [" + m.unit + "]") << "  " << m.meaning << "\n";
}

}  // namespace

void add_keys_command(CLI::App& app, GlobalOptions&) {
  auto kind = std::make_shared<std::string>();
  auto markdown = std::make_shared<bool>(false);
  CLI::App* sub = app.add_subcommand("keys", "a scene kind's rig keys (unit, range, default) and its metrics");
  sub->add_option("kind", *kind, "scene kind (none: list the kinds and the run report's metrics)");
  sub->add_flag("--markdown", *markdown, "print the tables of docs/scenes/KIND.md");
  sub->callback([kind, markdown] {
    const auto tables = scene_schema_tables();
    if (kind->empty()) {
      if (*markdown) {
        std::cout << run_report_markdown();
        return;
      }
      std::cout << "scene kinds with a rig schema:";
      for (const SchemaTable& t : tables) std::cout << " " << t.kind;
      std::cout << "\n(`impact` and `custom` declare bodies and walls: docs/scenes/impact.md, custom.md)\n"
                << "metrics every scene writes (the run report):\n";
      for (const SchemaMetric& m : run_report_metrics())
        std::cout << "  " << m.key << (m.unit.empty() ? "" : " [" + m.unit + "]") << "  " << m.meaning << "\n";
      return;
    }
    std::string kinds;
    for (const SchemaTable& t : tables) {
      kinds += (kinds.empty() ? "" : ", ") + t.kind;
      if (t.kind != *kind) continue;
      if (*markdown)
        std::cout << keys_markdown(t) << "\n" << metrics_markdown(t);
      else
        print_text(t);
      return;
    }
    throw InputError("seedcal keys: kind = \"" + *kind + "\" has no rig schema; allowed: " + kinds);
  });
}

}  // namespace seedcal
