#pragma once
// What the seed-scene runners share: filling the common part of a scene spec and drawing its
// seeds into a side view.
#include "calibrate/config/seed_config.hpp"
#include "calibrate/output/side_view_svg.hpp"
#include "calibrate/scenes/scene_registry.hpp"

namespace seedcal {

template <class Spec>
void fill_seed_spec(Spec& spec, const SeedSceneConfig& cfg, const SceneContext& ctx) {
  spec.physics = cfg.phys.physics;
  spec.time_step = cfg.phys.time_step;
  spec.seeds = cfg.seeds;
  spec.threads = ctx.threads;
  spec.seed = ctx.seed;
  spec.observer = ctx.observer;
}

inline void add_spheres(SideView& view, const std::vector<std::vector<std::pair<Vec3, double>>>& bodies) {
  for (const auto& body : bodies)
    for (const auto& [p, r] : body) view.circles.push_back({project(p, Eigen::Vector3d::UnitX()), r});
}

// The metrics every seed scene carries besides its own.
inline void add_seed_scene_keys(nlohmann::json& j, const SeedSceneConfig& cfg, const RunReport& run) {
  j["fidelity"] = cfg.fidelity;
  j["particle"] = cfg.particle_description;
  add_run_report(j, run);
}

}  // namespace seedcal
