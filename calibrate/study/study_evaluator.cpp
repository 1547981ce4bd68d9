#include "calibrate/study/study_evaluator.hpp"

#include <cmath>
#include <cstdio>

#include "calibrate/cli/errors.hpp"

namespace seedcal {

StudyEvaluator::StudyEvaluator(const StudyConfig& study, StudyStore& store, Executor& executor, Progress& progress)
    : study_(study), store_(store), executor_(executor), progress_(progress) {
  for (std::size_t i = 0; i < store_.evaluations().size(); ++i) stored_[store_.evaluations()[i].seed] = i;
}

std::vector<EvalRequest> StudyEvaluator::plan(const std::string& stage, const Eigen::VectorXd& natural, int replicates) {
  std::vector<EvalRequest> out;
  for (int rep = 0; rep < replicates; ++rep)
    for (std::size_t t = 0; t < study_.targets.size(); ++t) out.push_back(plan_one(stage, natural, static_cast<int>(t), 0));
  return out;
}

EvalRequest StudyEvaluator::plan_one(const std::string& stage, const Eigen::VectorXd& natural, int scene, int model,
                                     const std::string& out_dir) {
  EvalRequest r;
  r.stage = stage;
  r.target = scene;
  r.model = model;
  r.out_dir = out_dir;
  r.inputs = nlohmann::json::object();
  for (std::size_t p = 0; p < study_.parameters.size(); ++p) r.inputs[study_.parameters[p].path] = natural(static_cast<Eigen::Index>(p));
  // Seeds: the study seed's block of 2^20, one per planned run, never reused.
  r.seed = study_.seed * (std::uint64_t{1} << 20) + (++counter_);
  return r;
}

std::vector<EvaluationRecord> StudyEvaluator::run(const std::vector<EvalRequest>& requests,
                                                  const std::function<void(std::size_t, const EvaluationRecord&)>& on_record) {
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
    count_cpu(r);
    if (on_record) on_record(i, out[i]);
  }
  executor_.run(todo, [&](std::size_t k, EvaluationRecord rec) {
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
    out[where[k]] = std::move(rec);
    if (on_record) on_record(where[k], out[where[k]]);
  });
  for (const auto& r : out) {
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

Eigen::VectorXd StudyEvaluator::inputs_vector(const EvaluationRecord& r) const {
  Eigen::VectorXd x(static_cast<Eigen::Index>(study_.parameters.size()));
  for (std::size_t p = 0; p < study_.parameters.size(); ++p)
    x(static_cast<Eigen::Index>(p)) = r.inputs.at(study_.parameters[p].path).get<double>();
  return x;
}

}  // namespace seedcal
