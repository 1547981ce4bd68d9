#pragma once
// Pieces every scene shares: the material/interaction set, the time-step rule, and what a run
// reports about itself.
#include <cstdint>
#include <string>
#include <vector>

#include "solver/contact/contact_model.hpp"
#include "solver/core/materials.hpp"
#include "solver/sim/guards.hpp"
#include "solver/sim/simulation.hpp"

namespace seedcal {

struct PhysicsSpec {
  std::vector<Material> materials;
  std::vector<Interaction> interactions;
  ContactOptions contact;
  Vec3 gravity_m_s2 = Vec3(0.0, 0.0, -9.81);
};

struct TimeStepSpec {
  double dt_s = 0.0;               // 0: rayleigh_fraction x the Rayleigh step
  double rayleigh_fraction = 0.2;
  // False: rayleigh_fraction is the default, which is lowered to the stable limit where 0.2 of the
  // Rayleigh step would exceed it (soft or heavy particles at speed: E = 1e6 Pa, 1.7 m/s needs
  // 0.15), so every run inside the physical range completes without a setting. True: the user chose
  // it, and a fraction above the limit is refused.
  bool rayleigh_fraction_set = false;
  bool force_dt = false;           // run a step above the stable limit anyway
};

// The stable limit used to refuse a time step: the smaller of the Rayleigh step of the smallest
// sphere and a tenth of the shortest Hertz contact time at the expected impact speed (ten steps
// per contact is the least that resolves a collision; fewer and the explicit integrator gains
// energy). Documented in docs/time_step.md.
struct TimeStepLimits {
  double rayleigh_s = 0.0;
  double contact_time_s = 0.0;  // shortest Hertz contact time at the expected speed
  double impact_speed_m_s = 0.0;
  // What sets each part, for the refusal message: "'seed' sphere r = 0.004 m, E = 1e+11 Pa,
  // nu = 0.4, density 1340 kg/m3" and "'seed' on 'steel'".
  std::string rayleigh_from;
  std::string contact_from;
  double stable_limit_s() const;
};

TimeStepLimits time_step_limits(const Simulation& sim, double expected_impact_speed_m_s);

// Picks dt from the spec or throws SettingError("dt_s" / "rayleigh_fraction") naming the limit.
double choose_time_step(const TimeStepSpec& spec, const TimeStepLimits& limits);

// One phase of a scene's protocol as it ran (pour, settle, consolidate, shear, ...), named as the
// plan names it (run_plan.hpp): metrics.json shows it beside the plan's, so a run says where its
// time went and the plan's estimate of a phase that ends on a criterion can be checked.
struct PhaseRecord {
  std::string name;
  double simulated_s = 0.0;
  std::uint64_t steps = 0;
  double cpu_seconds = 0.0;
  // Where the phase began (the simulation's time, step count and CPU clock), until it is closed.
  double start_time_s = 0.0, start_cpu_s = 0.0;
  std::uint64_t start_step = 0;
};

struct RunReport {
  std::vector<PhaseRecord> phases;  // in order; begin_phase() opens one, finish_report() closes the last
  double cpu_seconds = 0.0;
  double wall_seconds = 0.0;
  std::uint64_t steps = 0;
  std::size_t bodies = 0;
  std::size_t spheres = 0;
  double dt_s = 0.0;
  std::string stop_reason;
  GuardFailure failure;  // status ok unless a guard stopped the run
  double deepest_overlap_fraction = 0.0;  // Simulation::deepest_overlap_fraction at the end
};

// CPU time of one run with `threads` OpenMP threads, s (a clock read; a run's time is the
// difference of two reads). One thread: the calling thread's CPU clock. Every parallel region of
// the solver runs on that thread alone then (`num_threads(threads)`, `if (threads > 1)`), so runs
// that share a process on other threads (`seedcal study trend --jobs`) are not counted. More
// threads: the whole process's CPU clock, which is the run's only when it has the process to
// itself (one simulation per process, as `seedcal run` and the calibration's workers have).
double run_cpu_seconds(int threads);

}  // namespace seedcal
