#include "calibrate/scenes/scene_file.hpp"

#include <filesystem>

#include "calibrate/cli/errors.hpp"
#include "calibrate/config/overrides.hpp"
#include "calibrate/config/toml_reader.hpp"
#include "calibrate/scenes/scene_registry.hpp"
#include "solver/core/errors.hpp"

namespace seedcal {

nlohmann::json run_scene_file(const std::string& path, const std::vector<std::string>& sets, int threads,
                              std::uint64_t seed, int repeats, const std::string& out_dir) {
  toml::value doc = TomlReader::parse_file(path);
  apply_overrides(doc, sets);
  const std::string kind = doc.contains("kind") && doc.at("kind").is_string() ? doc.at("kind").as_string().str : "";
  const auto& reg = scene_registry();
  const auto it = reg.find(kind);
  if (it == reg.end()) throw InputError(path + ": kind = \"" + kind + "\": unknown scene kind");
  if (!out_dir.empty()) std::filesystem::create_directories(out_dir);
  SceneContext ctx{path, out_dir, threads, seed};
  try {
    return run_repeated(it->second, doc, path, ctx, repeats);
  } catch (const SettingError& e) {
    throw InputError(path + ": " + e.what());
  }
}

}  // namespace seedcal
