#pragma once
// Stop criteria ("inspectors"): a scene runs until its index is settled, not for a fixed long
// time. Each returns why it stopped.
#include <cstdint>
#include <functional>
#include <string>

#include "solver/sim/simulation.hpp"

namespace seedcal {

struct SettleCriteria {
  // Settled when the mean kinetic energy per body, divided by (m g d) of a typical body falling one
  // diameter, drops below this ratio: 1e-4 means the bodies move at about 1 % of the speed they
  // gain falling one diameter (sqrt(2 g d) ~ 0.4 m/s for a 9 mm seed, so ~4 mm/s).
  double energy_ratio = 1e-4;
  double min_time_s = 0.0;    // never stop before
  double max_time_s = 10.0;   // give up (stop_reason says so)
  double check_interval_s = 1e-3;
};

struct SettleResult {
  bool settled = false;
  bool failed = false;  // a guard stopped the simulation (see sim.failure())
  std::string reason;
};

// Kinetic energy scale m g d of the mean body (d: twice the largest sphere radius).
double body_energy_scale_j(const Simulation& sim);

// Runs until settled, failed, or max_time_s; `each_check` (optional) is called at every check.
SettleResult run_until_settled(Simulation& sim, const SettleCriteria& c,
                               const std::function<void(const Simulation&)>& each_check = {});

// Runs for a duration (s), stopping early on a guard failure. Returns false on failure.
bool run_for(Simulation& sim, double duration_s);

}  // namespace seedcal
