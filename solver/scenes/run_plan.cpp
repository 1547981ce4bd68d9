#include "solver/scenes/run_plan.hpp"

#include <algorithm>
#include <cmath>

namespace seedcal {

double RunPlan::simulated_s() const {
  double t = 0.0;
  for (const PlanPhase& p : phases) t += p.simulated_s;
  return t;
}

double RunPlan::steps() const { return dt_s > 0.0 ? simulated_s() / dt_s : 0.0; }

double RunPlan::sphere_steps() const {
  if (!(dt_s > 0.0)) return 0.0;
  double s = 0.0;
  for (const PlanPhase& p : phases) s += p.spheres * p.simulated_s / dt_s;
  return s;
}

double seeds_in_mass(const SeedSpec& seeds, double mass_kg) {
  const double m = seeds.scale.mean, sd = seeds.scale.sd;
  const double seed_mass = seeds.body.mass_kg * (m * m * m + 3.0 * m * sd * sd);
  return seed_mass > 0.0 ? mass_kg / seed_mass : 0.0;
}

double pour_time_s(double mass_kg, double density_kg_m3, double region_m3, int batches, double interval_s) {
  constexpr double kInsertedFraction = 0.25;
  const double per_batch_kg = kInsertedFraction * region_m3 * density_kg_m3;
  const double n = per_batch_kg > 0.0 ? std::ceil(mass_kg / per_batch_kg) : batches;
  return std::clamp(n, 1.0, static_cast<double>(batches)) * interval_s;
}

double settle_time_s(double height_m, double gravity_m_s2, double max_time_s) {
  constexpr double kCollisionsDieOut_s = 0.1;
  const double fall = gravity_m_s2 > 0.0 ? std::sqrt(2.0 * std::max(0.0, height_m) / gravity_m_s2) : 0.0;
  return std::min(max_time_s, fall + kCollisionsDieOut_s);
}

}  // namespace seedcal
