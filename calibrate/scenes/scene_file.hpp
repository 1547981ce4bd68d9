#pragma once
// Runs a scene file in this process: read, apply overrides (--set paths), run `repeats` seeds
// through the scene registry, return the aggregated metrics (scene_registry.hpp, run_repeated).
// A bad config throws InputError; a failed simulation comes back with status != "ok".
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace seedcal {

nlohmann::json run_scene_file(const std::string& path, const std::vector<std::string>& sets, int threads,
                              std::uint64_t seed, int repeats, const std::string& out_dir = "");

}  // namespace seedcal
