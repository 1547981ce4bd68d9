#include "calibrate/pipeline/study_evaluator.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "calibrate/config/toml_reader.hpp"
#include "store/errors.hpp"

namespace seedcal {

StudyEvaluator::StudyEvaluator(const StudyConfig& study, StudyStore& store, Executor& executor, Progress& progress)
    : study_(study), store_(store), executor_(executor), progress_(progress) {
  for (std::size_t i = 0; i < store_.evaluations().size(); ++i) stored_[store_.evaluations()[i].seed] = i;
}

void StudyEvaluator::record_trajectories(const StudyTrajectories& trajectories, const std::string& out_dir) {
  std::string why;
  if (!trajectories.IsValid(&why)) throw std::invalid_argument("StudyEvaluator::record_trajectories: " + why);
  trajectories_ = trajectories;
  trajectory_dir_ = out_dir;
}

std::vector<EvalRequest> StudyEvaluator::plan(const std::string& stage, const Eigen::VectorXd& natural, int replicates) {
  // A confirmation's first replicate of each target records its trajectory when asked to.
  std::string round_dir;
  if (stage == "confirm") {
    char round[32];
    std::snprintf(round, sizeof round, "round_%02d", ++confirmations_);
    if (trajectories_.records(stage) && !trajectory_dir_.empty())
      round_dir = trajectory_dir_ + "/trajectories/confirm/" + round;
  }
  std::vector<EvalRequest> out;
  for (int rep = 0; rep < replicates; ++rep)
    for (std::size_t t = 0; t < study_.targets.size(); ++t)
      out.push_back(plan_one(stage, natural, static_cast<int>(t), calibration_model_,
                             rep == 0 && !round_dir.empty() ? round_dir + "/" + path_slug(study_.targets[t].name)
                                                            : std::string()));
  return out;
}

EvalRequest StudyEvaluator::plan_one(const std::string& stage, const Eigen::VectorXd& natural, int scene, int model,
                                     const std::string& out_dir) {
  EvalRequest r;
  r.stage = stage;
  r.target = scene;
  r.model = model;
  r.out_dir = out_dir;
  if (!out_dir.empty() && trajectories_.records(stage)) r.trajectory_interval_s = trajectories_.interval_s;
  r.inputs = nlohmann::json::object();
  for (std::size_t p = 0; p < study_.parameters.size(); ++p) r.inputs[study_.parameters[p].path] = natural(static_cast<Eigen::Index>(p));
  // Seeds: the study seed's block of 2^20, one per planned run, never reused.
  r.seed = study_.seed * (std::uint64_t{1} << 20) + (++counter_);
  return r;
}

std::vector<EvaluationRecord> StudyEvaluator::run(const std::vector<EvalRequest>& requests,
                                                  const std::function<void(std::size_t, const EvaluationRecord&)>& on_record,
                                                  const std::function<std::string(std::size_t)>& unneeded) {
  std::vector<EvaluationRecord> out(requests.size());
  std::vector<EvalRequest> todo;
  std::vector<std::size_t> where;
  for (std::size_t i = 0; i < requests.size(); ++i) {
    const auto it = stored_.find(requests[i].seed);
    if (it == stored_.end()) {
      todo.push_back(requests[i]);
      where.push_back(i);
      continue;
    }
    const EvaluationRecord& r = store_.evaluations()[it->second];
    if (r.stage != requests[i].stage || r.inputs != requests[i].inputs)
      throw RunFailed(store_.path() + ": evaluation with seed " + std::to_string(r.seed) + " is stage " + r.stage +
                      " at " + r.inputs.dump() + ", but the plan asks for stage " + requests[i].stage + " at " +
                      requests[i].inputs.dump() + ": the store was written by a different plan (another seedcal "
                      "version?); start a new --out directory");
    out[i] = r;
    ++reused_;
    progress_.run_done(true, r.wall_seconds, "seed " + std::to_string(r.seed) + " " + r.status);
    refuse_missing_metric(r);
    count_cpu(r);
    if (on_record) on_record(i, out[i]);
  }
  DispatchCheck check;
  if (unneeded)
    check = [&](std::size_t k) -> std::optional<EvaluationRecord> {
      const std::string why = unneeded(where[k]);
      if (why.empty()) return std::nullopt;
      EvaluationRecord rec = request_record(study_, todo[k]);
      rec.status = "skipped";
      rec.message = why;
      return rec;
    };
  executor_.run(todo, [&](std::size_t k, EvaluationRecord rec) {
    if (rec.status == "skipped") {
      progress_.run_skipped("seed " + std::to_string(rec.seed) + " target " +
                            rec.metrics.value("study_target_name", "?") + ": " + rec.message);
      out[where[k]] = std::move(rec);
      if (on_record) on_record(where[k], out[where[k]]);
      return;
    }
    rec.id = 0;
    store_.append(rec);  // on disk before anything else happens
    rec = store_.evaluations().back();
    stored_[rec.seed] = store_.evaluations().size() - 1;
    const double v = record_metric(study_, rec);
    char what[256];
    std::snprintf(what, sizeof what, "seed %llu target %s: %s %.6g (%.1f s)", static_cast<unsigned long long>(rec.seed),
                  rec.metrics.value("study_target_name", "?").c_str(), rec.status.c_str(), v, rec.wall_seconds);
    progress_.run_done(false, rec.wall_seconds, std::string(what) + (rec.status == "ok" ? "" : ": " + rec.message));
    count_cpu(rec);
    refuse_missing_metric(rec);
    out[where[k]] = std::move(rec);
    if (on_record) on_record(where[k], out[where[k]]);
  }, check);
  for (const auto& r : out) {
    if (r.status == "skipped") continue;  // not a DEM run
    history_.push_back(r);
    ++used_;
    const int t = record_target(r);
    const double v = record_metric(study_, r);
    if (t >= 0 && t < static_cast<int>(study_.targets.size()) && r.metrics.value("study_model", "").empty() &&
        std::isfinite(v))
      progress_.best_error(v / study_.targets[static_cast<std::size_t>(t)].value - 1.0);
  }
  return out;
}

// A run that the scene finished ("ok") but whose metrics lack the study's metric key is a study
// file error (a misspelt metric), not a failed run: every other run would fail the same way, so
// the study stops at the first one (its record is stored) with the scene's metric keys.
void StudyEvaluator::refuse_missing_metric(const EvaluationRecord& rec) const {
  if (rec.status == "ok" || rec.metrics.value("status", std::string()) != "ok") return;
  const int t = record_target(rec);
  if (t < 0 || t >= study_.scene_count()) return;
  const StudyTarget& target = study_.scene_of(t);
  if (rec.metrics.contains(target.metric)) return;  // present but not finite: the run's problem
  // A non-finite index is removed from the metrics and listed (scene_registry.cpp): also the run's
  // problem, not the study file's.
  for (const auto& removed : rec.metrics.value("non_finite_removed", nlohmann::json::array()))
    if (removed.is_string() && removed.get<std::string>() == target.metric) return;
  std::vector<std::string> keys;
  for (const auto& [key, value] : rec.metrics.items())
    if (value.is_number() && key.rfind("study_", 0) != 0) keys.push_back(key);
  std::string msg = study_.file + ": " + (t < static_cast<int>(study_.targets.size()) ? "target" : "verification test") +
                    " \"" + target.name + "\": metric = \"" + target.metric + "\": " + target.scene +
                    " reports no such metric";
  const std::string hint = did_you_mean(target.metric, keys);
  if (!hint.empty()) msg += " (did you mean \"" + hint + "\"?)";
  std::string list;
  for (const auto& k : keys) list += (list.empty() ? "" : ", ") + k;
  throw InputError(msg + "; its metrics: " + list);
}

Eigen::VectorXd StudyEvaluator::inputs_vector(const EvaluationRecord& r) const {
  Eigen::VectorXd x(static_cast<Eigen::Index>(study_.parameters.size()));
  for (std::size_t p = 0; p < study_.parameters.size(); ++p)
    x(static_cast<Eigen::Index>(p)) = r.inputs.at(study_.parameters[p].path).get<double>();
  return x;
}

}  // namespace seedcal
