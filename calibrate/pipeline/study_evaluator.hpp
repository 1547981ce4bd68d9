#pragma once
// The planner's one door to DEM runs: gives each planned request its seed (a counter in plan
// order, so every seed is used once and a resumed study plans the same seeds), answers requests
// already in the store from the store, runs the others on the executor, and appends each record
// to the store the moment it arrives.
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "calibrate/pipeline/executor.hpp"
#include "calibrate/pipeline/progress.hpp"
#include "calibrate/pipeline/study_config.hpp"
#include "calibrate/pipeline/study_trajectories.hpp"
#include "store/study_store.hpp"

namespace seedcal {

class StudyEvaluator {
 public:
  StudyEvaluator(const StudyConfig& study, StudyStore& store, Executor& executor, Progress& progress);

  // A request for every target at `natural` (one value per study parameter).
  std::vector<EvalRequest> plan(const std::string& stage, const Eigen::VectorXd& natural, int replicates);
  // One request: scene `scene` (StudyConfig::scene_of) under model `model`; `out_dir` asks the
  // scene to write its CSV and picture there.
  EvalRequest plan_one(const std::string& stage, const Eigen::VectorXd& natural, int scene, int model,
                       const std::string& out_dir = "");
  // From now on, the runs `trajectories` names record their trajectories under `out_dir`
  // (study_trajectories.hpp): plan_one marks a request of a recorded stage that has an out_dir,
  // and plan gives the first replicate of a confirmation its folder under out_dir/trajectories/.
  void record_trajectories(const StudyTrajectories& trajectories, const std::string& out_dir);
  // Runs the requests (store first), returns the records in request order. `on_record`, when
  // set, is called with each request's index and record as it arrives (stored ones first).
  // `unneeded`, when set, is asked just before a request not in the store would start: a
  // non-empty reason skips it (a run whose result can no longer change the study's outcome). A
  // skipped request gets a record with status "skipped" and the reason; it is not a DEM run, so
  // it is neither stored nor counted (a resumed study skips it again for the same reason).
  std::vector<EvaluationRecord> run(const std::vector<EvalRequest>& requests,
                                    const std::function<void(std::size_t, const EvaluationRecord&)>& on_record = {},
                                    const std::function<std::string(std::size_t)>& unneeded = {});

  // Tells the progress display a new stage (or round) begins with `planned` runs.
  void announce(const std::string& stage, int planned) { progress_.stage(stage, planned); }
  // The model plan() runs the targets under (StudyConfig::models; 0 by default): the calibration of
  // each model with [verify] calibrate_each_model.
  void set_calibration_model(int model) { calibration_model_ = model; }
  int calibration_model() const { return calibration_model_; }
  void note(const std::string& message) { progress_.log(message); }

  int runs_used() const { return used_; }        // DEM runs of this plan so far (replicates included)
  int runs_reused() const { return reused_; }    // of those, answered from the store
  // Every record of this plan so far, in plan order (a batch joins when the whole batch is in).
  const std::vector<EvaluationRecord>& history() const { return history_; }
  // CPU seconds of this plan's records so far, counted as each record arrives (also mid-batch):
  // the verification runs and all the others.
  double verification_cpu_seconds() const { return cpu_verify_; }
  double calibration_cpu_seconds() const { return cpu_other_; }
  const StudyConfig& study() const { return study_; }
  Eigen::VectorXd inputs_vector(const EvaluationRecord& r) const;  // natural, study order

 private:
  const StudyConfig& study_;
  StudyStore& store_;
  Executor& executor_;
  Progress& progress_;
  std::uint64_t counter_ = 0;
  StudyTrajectories trajectories_;
  std::string trajectory_dir_;
  int confirmations_ = 0;
  int calibration_model_ = 0;  // plan("confirm") calls so far: the rounds' folder numbers
  std::map<std::uint64_t, std::size_t> stored_;  // seed -> index in the store
  std::vector<EvaluationRecord> history_;
  int used_ = 0, reused_ = 0;
  double cpu_verify_ = 0.0, cpu_other_ = 0.0;
  void refuse_missing_metric(const EvaluationRecord& rec) const;
  void count_cpu(const EvaluationRecord& r) { (r.stage == "verify" ? cpu_verify_ : cpu_other_) += r.cpu_seconds; }
};

}  // namespace seedcal
