#pragma once
// Wall time per phase of a step (StepProfile, sim/simulation.hpp), taken only when profiling.
#include <chrono>

namespace seedcal {

// Adds the time since `t0` to `acc` and restarts `t0`, when profiling.
inline void lap(bool on, std::chrono::steady_clock::time_point& t0, double& acc) {
  if (!on) return;
  const auto t1 = std::chrono::steady_clock::now();
  acc += std::chrono::duration<double>(t1 - t0).count();
  t0 = t1;
}

}  // namespace seedcal
