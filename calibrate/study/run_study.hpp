#pragma once
// `seedcal calibrate`: runs a study end to end into DIR (study.h5, summary.json, calibrate.log),
// or resumes one.
#include <string>
#include <vector>

#include "calibrate/study/executor.hpp"

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
  // (io/study_lock.hpp).
  bool force_unlock = false;
};

// Returns the summary (also written to DIR/summary.json). `executor` may be null: a worker pool
// of `jobs` processes is used.
nlohmann::json run_study(const StudyRunOptions& options, Executor* executor);

// The worker command line for this study (for make_worker_pool).
WorkerCommand worker_command(const StudyRunOptions& options);

}  // namespace seedcal
