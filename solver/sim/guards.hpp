#pragma once
// Stability guards: a run that goes wrong stops with the step, the body and the likely cause
// instead of writing NaN or exploding silently.
#include <cstdint>
#include <string>

namespace seedcal {

struct GuardOptions {
  // Deepest allowed overlap as a fraction of the smaller radius. Hertz theory assumes
  // overlap << radius; past half a radius the model means nothing and the usual cause is a too
  // soft material or a too large time step.
  double max_overlap_fraction = 0.5;
  // Kinetic energy may not exceed this multiple of the energy the scene can supply (initial
  // kinetic + potential energy above the lowest point + work of moving walls, see simulation.cpp).
  double max_energy_factor = 10.0;
  // Steps between energy checks (NaN is checked every step).
  int check_interval = 200;
};

enum class RunStatus { ok, non_finite, energy_runaway, deep_overlap, aborted };
const char* to_string(RunStatus s);

struct GuardFailure {
  RunStatus status = RunStatus::ok;
  std::uint64_t step = 0;
  double time_s = 0.0;
  std::int64_t body = -1;
  std::string message;
};

}  // namespace seedcal
