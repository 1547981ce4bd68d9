#include "solver/scenes/seed_bed.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "solver/sim/memory_estimate.hpp"

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

void check_pour_memory(const PhysicsSpec& physics, const SeedSpec& seeds, double mass_kg, int threads,
                       const std::string& key, const std::string& rig) {
  // Mean seed mass: template mass x E[s^3] (as seed_volume_m3).
  const double m = seeds.scale.mean, sd = seeds.scale.sd;
  const double seed_mass = seeds.body.mass_kg * (m * m * m + 3.0 * m * sd * sd);
  if (!(seed_mass > 0.0) || !(mass_kg > 0.0)) return;
  const double count = std::ceil(mass_kg / seed_mass);
  const double spheres = count * static_cast<double>(seeds.body.spheres.size());
  // Beyond 2^53 the count is not even representable; such a rig is refused all the same.
  const double cap = 9.0e15;
  const MemoryEstimate est =
      estimate_memory(static_cast<std::size_t>(std::min(count, cap)),
                      static_cast<std::size_t>(std::min(spheres, cap)), threads,
                      physics.contact.rolling == RollingModel::epsd);
  std::ostringstream what;
  what.precision(3);
  what << rig << " takes about " << count << " seeds (" << mass_kg << " kg)";
  check_memory(est, available_memory_bytes(), key, what.str());
}

std::string describe_rig(std::initializer_list<std::pair<const char*, double>> keys) {
  std::ostringstream s;
  s.precision(4);
  const char* sep = "";
  for (const auto& [k, v] : keys) {
    s << sep << k << " = " << v;
    sep = ", ";
  }
  return s.str();
}

SimulationOptions seed_options(const PhysicsSpec& physics, double dt_s, int threads, std::uint64_t seed,
                               const FrameObserver& observer) {
  SimulationOptions opt;
  opt.contact = physics.contact;
  opt.gravity_m_s2 = physics.gravity_m_s2;
  opt.dt_s = dt_s;
  opt.threads = threads;
  opt.seed = seed;
  opt.observer = observer;
  return opt;
}

double pour_seeds(Simulation& sim, const FactorySpec& spec, double mass_kg, int batches, double fall_s) {
  double poured = 0.0;
  for (int batch = 0; batch < batches && poured < mass_kg; ++batch) {
    FactorySpec b = spec;
    b.total_mass_kg = mass_kg - poured;
    b.max_attempts = 100000;
    const FactoryResult r = insert_particles(sim, b);
    poured += r.mass_kg;
    if (r.placed == 0) break;
    const auto steps = static_cast<std::uint64_t>(fall_s / sim.options().dt_s);
    if (!sim.run(steps)) break;
  }
  return poured;
}

double highest_point_m(const Simulation& sim) {
  const SphereState& S = sim.spheres();
  double top = 0.0;
  for (std::size_t i = 0; i < S.size(); ++i) top = std::max(top, S.position_m[i].z() + S.radius_m[i]);
  return top;
}

std::vector<std::vector<std::pair<Vec3, double>>> body_spheres(const Simulation& sim) {
  const BodyState& B = sim.bodies();
  std::vector<std::vector<std::pair<Vec3, double>>> out;
  for (std::size_t b = 0; b < B.size(); ++b) {
    std::vector<std::pair<Vec3, double>> sp;
    for (std::uint32_t s = B.first_sphere[b]; s < B.first_sphere[b + 1]; ++s)
      sp.push_back({sim.spheres().position_m[s], sim.spheres().radius_m[s]});
    out.push_back(std::move(sp));
  }
  return out;
}

void end_phase(RunReport& r, const Simulation& sim) {
  if (r.phases.empty()) return;
  PhaseRecord& p = r.phases.back();
  p.simulated_s = sim.time_s() - p.start_time_s;
  p.steps = sim.step_count() - p.start_step;
  p.cpu_seconds = run_cpu_seconds(sim.options().threads) - p.start_cpu_s;
}

void begin_phase(RunReport& r, const Simulation& sim, const std::string& name) {
  end_phase(r, sim);
  PhaseRecord p;
  p.name = name;
  p.start_time_s = sim.time_s();
  p.start_step = sim.step_count();
  p.start_cpu_s = run_cpu_seconds(sim.options().threads);
  r.phases.push_back(std::move(p));
}

void finish_report(RunReport& r, Simulation& sim, double cpu0_s,
                   std::chrono::steady_clock::time_point wall_t0) {
  if (sim.failure().status == RunStatus::ok && !sim.final_check())
    r.stop_reason = std::string("guard: ") + to_string(sim.failure().status);
  end_phase(r, sim);
  r.failure = sim.failure();
  r.steps = sim.step_count();
  r.deepest_overlap_fraction = sim.deepest_overlap_fraction();
  r.bodies = sim.bodies().size();
  r.spheres = sim.spheres().size();
  r.dt_s = sim.options().dt_s;
  r.cpu_seconds = run_cpu_seconds(sim.options().threads) - cpu0_s;
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_t0).count();
}

double seed_volume_m3(const SeedSpec& seeds, double density_kg_m3) {
  // E[s^3] of the (truncated) normal is close to mean^3 + 3 mean sd^2.
  const double m = seeds.scale.mean, s = seeds.scale.sd;
  return seeds.body.mass_kg / density_kg_m3 * (m * m * m + 3.0 * m * s * s);
}

}  // namespace seedcal
