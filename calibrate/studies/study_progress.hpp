#pragma once
// What a `seedcal study` will run and how far it has come. Before the first run: its planned DEM
// runs (each a scene file with its overrides and a number of runs), priced on this machine as
// `seedcal calibrate` prices a study (calibrate/pipeline/cost_estimate.hpp). While it runs: a status
// line on a terminal (runs done of planned, elapsed, time left from the estimate scaled by what the
// runs so far took against theirs); nothing is drawn when it is off.
#include <chrono>
#include <mutex>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "calibrate/pipeline/cost_estimate.hpp"

namespace seedcal {

struct PlannedRuns {
  std::string label;              // "rayleigh_fraction = 0.2"
  std::string scene;              // scene file
  std::vector<std::string> sets;  // its overrides
  int runs = 1;
  // Whether the study records a scene's refusal of these settings as a row and goes on (a tradeoff
  // row past the reference); otherwise a refusal is bad input, as the study itself would say.
  bool refusal_is_a_row = false;
};

struct StudyPlanEstimate {
  std::vector<std::pair<PlannedRuns, SceneCost>> rows;
  int runs = 0;
  double cpu_s = 0.0, probe_cpu_s = 0.0;
};

// Prices every row (`threads` per simulation). A row the scene refuses is bad input (InputError).
StudyPlanEstimate estimate_study_plan(const std::vector<PlannedRuns>& plan, int threads);
// The estimate in lines; `slots` simulations at once.
std::vector<std::string> describe_study_plan(const std::string& kind, const StudyPlanEstimate& e, int slots);
nlohmann::json study_plan_json(const StudyPlanEstimate& e);

class StudyProgress {
 public:
  StudyProgress(std::string kind, const StudyPlanEstimate& estimate, int slots, bool terminal);
  StudyProgress(const StudyProgress&) = delete;
  StudyProgress& operator=(const StudyProgress&) = delete;
  ~StudyProgress();  // clears the line

  // `runs` runs finished that were estimated at `estimated_cpu_s` and took `cpu_s` (thread-safe).
  void runs_done(int runs, double estimated_cpu_s, double cpu_s);
  // After a scene call: its metrics (their runs and cpu_seconds) against the row's estimate.
  void scene_done(const std::string& scene, const std::vector<std::string>& sets, const nlohmann::json& metrics);
  void clear();

 private:
  std::string kind_;
  std::vector<std::pair<PlannedRuns, SceneCost>> rows_;
  int planned_;
  double estimated_cpu_s_;
  int slots_;
  bool on_;
  std::mutex mutex_;
  int done_ = 0;
  double done_estimated_s_ = 0.0, done_cpu_s_ = 0.0;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace seedcal
