#pragma once
// One DEM evaluation of a study: a target's scene run once at given parameter values with a given
// seed. Requests are planned deterministically (their seeds come from a counter in plan order), so
// a resumed study asks for exactly the same requests and finds the finished ones in the store.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "calibrate/pipeline/study_config.hpp"
#include "store/study_store.hpp"

namespace seedcal {

struct EvalRequest {
  std::string stage;              // screen, ascent, surrogate, confirm, infill
  int target = 0;                 // StudyConfig::scene_of index: a target, then the verification tests
  int model = 0;                  // index into StudyConfig::models (its overrides apply first)
  nlohmann::json inputs;          // parameter path -> natural value (every study parameter)
  std::uint64_t seed = 0;         // unique within the study
  std::string out_dir;            // when set, the scene also writes its CSV and picture here
  // > 0 with out_dir set: the scene also records its trajectory there, a frame every this many
  // simulated seconds (study_trajectories.hpp); the run's result is the same.
  double trajectory_interval_s = 0.0;

  nlohmann::json to_json() const;
  static EvalRequest from_json(const nlohmann::json& j);
};

// The overrides a study run applies to its scene: the model's, then the test's, then every
// parameter at `inputs` (path -> natural value) as a TOML float (a request that records its
// trajectory adds [output] trajectory and trajectory_interval_s after them, in evaluate()).
std::vector<std::string> scene_overrides(const StudyModel& model, const StudyTarget& test, const nlohmann::json& inputs);

// A record of `request` without a result: its stage, inputs and seed, and the metrics that tie it
// to its scene (study_target, study_target_name) and model (study_model, for models after the
// first). `evaluate` fills in the rest; a run the study skips is reported as such a record.
EvaluationRecord request_record(const StudyConfig& study, const EvalRequest& request);

// Runs the request in this process with `threads` OpenMP threads; never throws for a failed or
// unstable simulation or a scene error: the record says "failed" and why.
EvaluationRecord evaluate(const StudyConfig& study, const EvalRequest& request, int threads,
                          const std::string& config_hash);

// The value of the record's scene metric (target or verification test; NaN when the run failed or
// lacks it).
double record_metric(const StudyConfig& study, const EvaluationRecord& r);
// The target index a record belongs to (from its metrics), -1 when unknown.
int record_target(const EvaluationRecord& r);
// The model a record ran under (StudyConfig::models; its `study_model`, 0 when it names none), -1
// when it names a model the study does not have.
int record_model(const StudyConfig& study, const EvaluationRecord& r);

}  // namespace seedcal
