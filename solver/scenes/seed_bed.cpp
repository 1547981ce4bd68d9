#include "solver/scenes/seed_bed.hpp"

#include <cmath>

namespace seedcal {

double seed_time_step(const PhysicsSpec& physics, const TimeStepSpec& ts, const SeedSpec& seeds,
                      double impact_speed_m_s) {
  SimulationOptions opt;
  opt.dt_s = 1.0;
  opt.contact = physics.contact;
  opt.gravity_m_s2 = physics.gravity_m_s2;
  Simulation probe(InteractionTable(physics.materials, physics.interactions), opt);
  const double s_min = seeds.scale.sd > 0.0 ? seeds.scale.lo : seeds.scale.mean;
  probe.add_body(scaled_body(seeds.body, s_min));
  return choose_time_step(ts, time_step_limits(probe, impact_speed_m_s));
}

SimulationOptions seed_options(const PhysicsSpec& physics, double dt_s, int threads, std::uint64_t seed) {
  SimulationOptions opt;
  opt.contact = physics.contact;
  opt.gravity_m_s2 = physics.gravity_m_s2;
  opt.dt_s = dt_s;
  opt.threads = threads;
  opt.seed = seed;
  return opt;
}

double seed_volume_m3(const SeedSpec& seeds, double density_kg_m3) {
  // E[s^3] of the (truncated) normal is close to mean^3 + 3 mean sd^2.
  const double m = seeds.scale.mean, s = seeds.scale.sd;
  return seeds.body.mass_kg / density_kg_m3 * (m * m * m + 3.0 * m * s * s);
}

}  // namespace seedcal
