#pragma once
// What a running study tells its user: the stage, runs done / planned, the best relative error so
// far, elapsed and estimated remaining time. On a terminal one status line is redrawn; otherwise
// nothing is drawn. Every event also goes, time-stamped, to DIR/calibrate.log.
#include <chrono>
#include <fstream>
#include <string>

namespace seedcal {

// The current UTC time as ISO 8601 (YYYY-MM-DDThh:mm:ssZ).
std::string utc_now();

// A duration as h:mm:ss ("0:12:27"); "?" when it is unknown (negative or not finite).
std::string clock_text(double seconds);

class Progress {
 public:
  Progress(const std::string& log_path, bool terminal, int slots);
  ~Progress();
  void stage(const std::string& name, int planned);  // a new stage with `planned` DEM runs
  void run_done(bool reused, double wall_seconds, const std::string& what);
  // A planned run that the study skipped (not run; not in the time estimate).
  void run_skipped(const std::string& what);
  void best_error(double relative_error);             // smallest |relative error| seen so far
  void log(const std::string& message);               // a line in the log (and on the terminal)
  double elapsed_seconds() const;

 private:
  void draw();
  // Counts a planned run as done and logs it: "STAGE k/n" + `tag` + `what`.
  void count_run(const char* tag, const std::string& what);
  std::ofstream log_;
  bool terminal_;
  int slots_;
  std::string stage_;
  int planned_ = 0, done_ = 0, total_done_ = 0;
  double run_wall_sum_ = 0.0;
  int run_wall_count_ = 0;
  double best_ = -1.0;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace seedcal
