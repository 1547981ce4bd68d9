#include "calibrate/pipeline/evaluation.hpp"

#include <chrono>
#include <cmath>
#include <ctime>
#include <limits>

#include "calibrate/scenes/scene_file.hpp"
#include "solver/core/errors.hpp"
#include "store/version.hpp"

namespace seedcal {
namespace {

std::string number_text(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  std::string s = buf;
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";  // a TOML float, not an integer
  return s;
}

}  // namespace

std::vector<std::string> scene_overrides(const StudyModel& model, const StudyTarget& test, const nlohmann::json& inputs) {
  std::vector<std::string> sets = model.sets;
  sets.insert(sets.end(), test.sets.begin(), test.sets.end());
  for (const auto& [path, value] : inputs.items()) sets.push_back(path + "=" + number_text(value.get<double>()));
  return sets;
}

nlohmann::json EvalRequest::to_json() const {
  nlohmann::json j = {{"stage", stage}, {"target", target}, {"inputs", inputs}, {"seed", seed}};
  if (model != 0) j["model"] = model;
  if (!out_dir.empty()) j["out_dir"] = out_dir;
  if (trajectory_interval_s > 0.0) j["trajectory_interval_s"] = trajectory_interval_s;
  return j;
}

EvalRequest EvalRequest::from_json(const nlohmann::json& j) {
  EvalRequest r;
  r.stage = j.at("stage").get<std::string>();
  r.target = j.at("target").get<int>();
  r.inputs = j.at("inputs");
  r.seed = j.at("seed").get<std::uint64_t>();
  r.model = j.value("model", 0);
  r.out_dir = j.value("out_dir", std::string());
  r.trajectory_interval_s = j.value("trajectory_interval_s", 0.0);
  return r;
}

EvaluationRecord request_record(const StudyConfig& study, const EvalRequest& request) {
  EvaluationRecord rec;
  rec.stage = request.stage;
  rec.inputs = request.inputs;
  rec.seed = request.seed;
  rec.metrics = {{"study_target", request.target}, {"study_target_name", study.scene_of(request.target).name}};
  if (request.model != 0) rec.metrics["study_model"] = study.models.at(static_cast<std::size_t>(request.model)).name;
  return rec;
}

EvaluationRecord evaluate(const StudyConfig& study, const EvalRequest& request, int threads,
                          const std::string& config_hash) {
  EvaluationRecord rec = request_record(study, request);
  const nlohmann::json tags = rec.metrics;
  rec.config_hash = config_hash;
  rec.seedcal_version = version_string();
  const StudyTarget& target = study.scene_of(request.target);
  const StudyModel& model = study.models.at(static_cast<std::size_t>(request.model));
  const auto wall0 = std::chrono::steady_clock::now();
  const std::clock_t cpu0 = std::clock();
  try {
    std::vector<std::string> sets = scene_overrides(model, target, request.inputs);
    if (request.trajectory_interval_s > 0.0 && !request.out_dir.empty()) {
      sets.push_back("output.trajectory=true");
      sets.push_back("output.trajectory_interval_s=" + number_text(request.trajectory_interval_s));
    }
    rec.metrics = run_scene_file(target.scene, sets, threads, request.seed, 1, request.out_dir);
    rec.status = rec.metrics.value("status", "ok");
    if (rec.status != "ok" && rec.metrics.contains("failure"))
      rec.message = rec.metrics["failure"].value("message", "");
    if (rec.status == "ok") {
      const auto m = rec.metrics.find(target.metric);
      if (m == rec.metrics.end() || !m->is_number() || !std::isfinite(m->get<double>())) {
        rec.status = "failed";
        rec.message = target.scene + ": the scene's metrics have no finite \"" + target.metric + "\"";
      }
    }
  } catch (const SettingError& e) {
    rec.status = "failed";
    rec.message = target.scene + ": " + e.what();
  } catch (const std::exception& e) {
    rec.status = "failed";
    rec.message = e.what();
  }
  if (rec.metrics.contains("runs")) rec.metrics.erase("runs");  // one run: the same numbers again
  rec.metrics.update(tags);  // the scene's metrics replaced them
  rec.cpu_seconds = rec.metrics.value("cpu_seconds", static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC);
  rec.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return rec;
}

double record_metric(const StudyConfig& study, const EvaluationRecord& r) {
  const int t = record_target(r);
  if (r.status != "ok" || t < 0 || t >= study.scene_count()) return std::numeric_limits<double>::quiet_NaN();
  const auto m = r.metrics.find(study.scene_of(t).metric);
  return m != r.metrics.end() && m->is_number() ? m->get<double>() : std::numeric_limits<double>::quiet_NaN();
}

int record_target(const EvaluationRecord& r) { return r.metrics.value("study_target", -1); }

int record_model(const StudyConfig& study, const EvaluationRecord& r) {
  const std::string name = r.metrics.value("study_model", std::string());
  if (name.empty()) return 0;
  for (std::size_t m = 0; m < study.models.size(); ++m)
    if (study.models[m].name == name) return static_cast<int>(m);
  return -1;
}

}  // namespace seedcal
