#include "calibrate/scenes/scene_registry.hpp"

namespace seedcal {

const std::map<std::string, SceneRunner>& scene_registry() {
  static const std::map<std::string, SceneRunner> kScenes = {
      {"impact", run_impact_scene},
  };
  return kScenes;
}

void add_run_report(nlohmann::json& j, const RunReport& r) {
  j["cpu_seconds"] = r.cpu_seconds;
  j["wall_seconds"] = r.wall_seconds;
  j["steps"] = r.steps;
  j["bodies"] = r.bodies;
  j["spheres"] = r.spheres;
  j["dt_s"] = r.dt_s;
  j["stop_reason"] = r.stop_reason;
  j["status"] = to_string(r.failure.status);
  if (r.failure.status != RunStatus::ok) {
    j["failure"] = {{"step", r.failure.step},
                    {"time_s", r.failure.time_s},
                    {"body", r.failure.body},
                    {"message", r.failure.message}};
  }
}

}  // namespace seedcal
