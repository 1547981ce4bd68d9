#pragma once
// `seedcal calibrate`: runs a study end to end into DIR (study.h5, summary.json, calibrate.log),
// or resumes one.
#include <functional>
#include <string>
#include <vector>

#include "calibrate/pipeline/executor.hpp"
#include "calibrate/pipeline/study_trajectories.hpp"

namespace seedcal {

struct StudyRunOptions {
  std::string study_file;
  std::vector<std::string> sets;
  std::string out_dir;
  bool resume = false;
  int jobs = 1;
  int threads = 1;
  bool progress_on_terminal = true;
  // Take over the study directory's lock even when it is held from another machine
  // (store/study_lock.hpp).
  bool force_unlock = false;
  // Print the study's plan and cost estimate (cost_estimate.hpp) and run nothing: no executor is
  // started and DIR is not touched; `jobs` gives the slots of the wall-time estimate.
  bool dry_run = false;
  // Runs whose trajectories are recorded (--trajectory; study_trajectories.hpp).
  StudyTrajectories trajectories;
  // Renders the report from DIR (the app passes reports/'s renderer): called after each verified
  // model and at the end; a report that cannot be written is logged and does not fail the study.
  std::function<void(const std::string& out_dir)> render_report;
};

// Returns the summary (also written to DIR/summary.json). The simulations run on the executor
// `make_executor` returns for the study's fingerprint. Before the first run the plan and its cost
// estimate go to stderr and the log; with dry_run they go to stdout and the estimate is returned.
nlohmann::json run_study(const StudyRunOptions& options, const ExecutorFactory& make_executor);

}  // namespace seedcal
