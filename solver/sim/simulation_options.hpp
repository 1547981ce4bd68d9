#pragma once
// The options of a Simulation, and their checks in one place (validate_options, called by the
// Simulation's constructor; set_time_step checks the step with the same function).
#include <cstdint>
#include <functional>

#include "solver/broadphase/pair_search.hpp"
#include "solver/contact/contact_model.hpp"
#include "solver/core/vec.hpp"
#include "solver/sim/guards.hpp"

namespace seedcal {

class Simulation;

// Frames of a run for output (a trajectory): on_frame(sim) is called at the first step (t = 0),
// at the start of the first step at or after each multiple of interval_s, when a guard stops the
// run (the state that stopped it) and from final_check() (the state the scene ends with), never
// twice for the same step. It sees the simulation read-only, so the run is the same with or
// without it; unset (no on_frame), it costs one comparison per step. One simulation per observer:
// a scene that runs several passes the observer to the one it measures.
//
// Progress (optional, for a status line, never for output): on_progress(sim) at the start of the
// first step at or after each multiple of progress_interval_s of simulated time; read-only too.
struct FrameObserver {
  double interval_s = 0.0;  // > 0 when on_frame is set
  std::function<void(const Simulation&)> on_frame;
  double progress_interval_s = 0.0;  // > 0 when on_progress is set
  std::function<void(const Simulation&)> on_progress;
};

struct SimulationOptions {
  ContactOptions contact;
  Vec3 gravity_m_s2 = Vec3(0.0, 0.0, -9.81);
  double dt_s = 0.0;    // must be set (see sim/time_step.hpp and choose_time_step())
  double skin_m = 0.0;  // Verlet skin; 0: 10 % of the largest sphere diameter
  int threads = 1;      // OpenMP threads inside this simulation
  GuardOptions guards;
  bool track_body_contacts = false;  // count sphere-level contacts per body each step
  bool profile = false;              // accumulate wall time per phase of the step (StepProfile)
  // Re-sort bodies (and their spheres) along a space-filling curve every this many steps, so
  // neighbours are near in memory (0: never), within one slab of the bed per thread (the order,
  // and so the bits, depend on `threads`). Worlds under 512 bodies and 8,192 spheres are never
  // sorted.
  std::uint64_t sort_interval_steps = 1000;
  std::uint64_t seed = 0;
  // Compute sphere-sphere and sphere-wall contacts this many at a time at most: 8 (AVX-512F), 4
  // (AVX2) or 1, the widest the CPU runs (sim/pair_batch.hpp); the results are the same bits at
  // any width.
  int simd_lanes = 8;
  // How the neighbour list finds its candidates (broadphase/pair_search.hpp): the same list, so
  // the same bits, whichever way; only the speed differs.
  PairSearch pair_search = PairSearch::automatic;
  FrameObserver observer;
};

// Throws std::invalid_argument naming the option and its allowed range when an option is out of
// range; sets threads < 1 to 1 (one thread, the serial run).
void validate_options(SimulationOptions& options);
// The time step's check: dt_s > 0 and finite. `where` names the caller in the message.
void require_time_step(double dt_s, const char* where);

}  // namespace seedcal
