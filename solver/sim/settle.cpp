#include "solver/sim/settle.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace seedcal {

double body_energy_scale_j(const Simulation& sim) {
  const auto& B = sim.bodies();
  if (B.size() == 0) return 0.0;
  double m = 0.0;
  for (double x : B.mass_kg) m += x;
  m /= static_cast<double>(B.size());
  double r = 0.0;
  for (double x : sim.spheres().radius_m) r = std::max(r, x);
  return m * std::max(sim.options().gravity_m_s2.norm(), 1.0) * 2.0 * r;
}

bool run_for(Simulation& sim, double duration_s) {
  const auto n = static_cast<std::uint64_t>(std::llround(duration_s / sim.options().dt_s));
  return sim.run(n);
}

SettleResult run_until_settled(Simulation& sim, const SettleCriteria& c,
                               const std::function<void(const Simulation&)>& each_check) {
  SettleResult r;
  const double scale = body_energy_scale_j(sim);
  const double t_end = sim.time_s() + c.max_time_s;
  const double t_min = sim.time_s() + c.min_time_s;
  const auto per_check =
      std::max<std::uint64_t>(1, static_cast<std::uint64_t>(c.check_interval_s / sim.options().dt_s));
  while (sim.time_s() < t_end) {
    if (!sim.run(per_check)) {
      r.failed = true;
      r.reason = std::string("guard: ") + to_string(sim.failure().status);
      return r;
    }
    if (each_check) each_check(sim);
    const double ratio = sim.bodies().size() > 0
                             ? sim.kinetic_energy_j() / static_cast<double>(sim.bodies().size()) / scale
                             : 0.0;
    if (sim.time_s() >= t_min && ratio < c.energy_ratio) {
      std::ostringstream s;
      s << "settled: kinetic energy per body " << ratio << " of m g d (< " << c.energy_ratio
        << ") at t = " << sim.time_s() << " s";
      r.settled = true;
      r.reason = s.str();
      return r;
    }
  }
  std::ostringstream s;
  s << "not settled within " << c.max_time_s << " s";
  r.reason = s.str();
  return r;
}

}  // namespace seedcal
