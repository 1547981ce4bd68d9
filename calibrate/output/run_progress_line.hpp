#pragma once
// The status line of `seedcal run` on a terminal: which run of the series, the simulated time
// against the plan's (run_plan.hpp), the spheres, steps per second, elapsed time and an estimate
// of the time left. Redrawn at most four times a second; runs that go at once (--jobs) share it.
// Nothing is drawn when the line is off (not a terminal, or --quiet).
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

#include "solver/scenes/run_plan.hpp"

namespace seedcal {

class RunProgressLine {
 public:
  RunProgressLine(const RunPlan& plan, int runs, int jobs, bool on);
  RunProgressLine(const RunProgressLine&) = delete;
  RunProgressLine& operator=(const RunProgressLine&) = delete;
  ~RunProgressLine();  // clears the line
  void clear();        // clears it now (before the command prints its result)

  // From a run's thread (SceneContext::progress).
  void update(std::size_t run, const Simulation& sim);
  bool on() const { return on_; }

  // The line for a state, for tests: `t_s` simulated seconds of run `run`, `steps_per_s`, the
  // wall seconds since the start, `left_s` (negative: unknown).
  static std::string format(std::size_t run, int runs, double t_s, double planned_s, std::size_t spheres,
                            double steps_per_s, double elapsed_s, double left_s);

 private:
  struct RunState {
    double t_s = 0.0;
    std::uint64_t step = 0;
    std::chrono::steady_clock::time_point last;
    double steps_per_s = 0.0;
  };
  double planned_s_;
  int runs_, jobs_;
  bool on_;
  std::mutex mutex_;
  std::vector<RunState> state_;
  std::chrono::steady_clock::time_point start_, last_draw_;
  double last_rate_ = 0.0;  // steps per second of the run last measured
};

}  // namespace seedcal
