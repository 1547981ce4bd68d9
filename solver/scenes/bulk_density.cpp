#include "solver/scenes/bulk_density.hpp"

#include <chrono>
#include <cmath>

#include "solver/sim/settle.hpp"
#include "solver/walls/box_shape.hpp"

namespace seedcal {

namespace {

// The protocol's phases, named once for its plan and its run (metrics.json `phases` beside
// `plan.phases`).
constexpr const char* kPhasePour = "pour";
constexpr const char* kPhaseSettle = "settle";

// Batches of the pour, each given this long to fall and make room for the next.
constexpr int kPourBatches = 20;
constexpr double kPourBatchInterval_s = 0.15;

}  // namespace

RunPlan plan_bulk_density(const BulkDensitySpec& spec) {
  const Vec3 c = spec.container_m;
  const double collar = spec.collar_fraction * c.z();
  const double g = spec.physics.gravity_m_s2.norm();
  const double rho = spec.physics.materials[spec.seeds.body.material].density_kg_m3;
  const double pour_kg = spec.overfill * c.x() * c.y() * c.z() * rho * 0.62;
  RunPlan p;
  p.dt_s = seed_time_step(spec.physics, spec.time_step, spec.seeds, std::sqrt(2.0 * g * (c.z() + collar)));
  p.body = spec.seeds.body;
  p.physics = spec.physics;
  p.seeds = seeds_in_mass(spec.seeds, pour_kg);
  p.spheres = p.seeds * static_cast<double>(spec.seeds.body.spheres.size());
  const double region_m3 = c.x() * c.y() * (0.7 * c.z() + collar);
  p.phases.push_back({kPhasePour, pour_time_s(pour_kg, rho, region_m3, kPourBatches, kPourBatchInterval_s),
                      0.5 * p.spheres, true});
  p.phases.push_back({kPhaseSettle, settle_time_s(c.z() + collar, g, spec.max_time_s), p.spheres, true});
  return p;
}

BulkDensityResult run_bulk_density(const BulkDensitySpec& spec) {
  const auto wall_t0 = std::chrono::steady_clock::now();
  const double cpu0 = run_cpu_seconds(spec.threads);
  BulkDensityResult res;
  const Vec3 c = spec.container_m;
  const double collar = spec.collar_fraction * c.z();
  const double g = spec.physics.gravity_m_s2.norm();
  const double dt = seed_time_step(spec.physics, spec.time_step, spec.seeds,
                                   std::sqrt(2.0 * g * (c.z() + collar)));
  const double rho = spec.physics.materials[spec.seeds.body.material].density_kg_m3;
  const double pour_kg = spec.overfill * c.x() * c.y() * c.z() * rho * 0.62;
  check_pour_memory(spec.physics, spec.seeds, pour_kg, spec.threads, "container_m",
                    describe_rig({{"container_m x", c.x()}, {"y", c.y()}, {"z", c.z()},
                                  {"overfill", spec.overfill}}));
  Simulation sim(InteractionTable(spec.physics.materials, spec.physics.interactions),
                 seed_options(spec.physics, dt, spec.threads, spec.seed, spec.observer));
  Wall box;
  box.name = "container";
  box.shape = std::make_shared<BoxShape>(Vec3(c.x(), c.y(), c.z() + collar), true);
  box.material = spec.wall_material;
  sim.add_wall(box);

  FactorySpec fs;
  fs.body = spec.seeds.body;
  fs.scale = spec.seeds.scale;
  fs.total_mass_kg = pour_kg;
  // Pour in layers: each batch fills the collar region, then settles a little before the next.
  fs.region.lo_m = Vec3(0.0, 0.0, 0.3 * c.z());
  fs.region.hi_m = Vec3(c.x(), c.y(), c.z() + collar);
  double poured = 0.0;
  begin_phase(res.run, sim, kPhasePour);
  for (int batch = 0; batch < kPourBatches && poured < fs.total_mass_kg; ++batch) {
    FactorySpec b = fs;
    b.total_mass_kg = fs.total_mass_kg - poured;
    b.max_attempts = 200000;
    const FactoryResult r = insert_particles(sim, b);
    poured += r.mass_kg;
    if (r.placed == 0) break;
    if (!run_for(sim, kPourBatchInterval_s)) break;  // let the batch fall and make room
    // Later batches go above what is already there.
    fs.region.lo_m.z() = std::min(highest_point_m(sim), c.z() + collar - 0.02);
  }
  res.seeds_poured = sim.bodies().size();
  begin_phase(res.run, sim, kPhaseSettle);
  SettleResult st;
  if (sim.failure().status == RunStatus::ok) {
    SettleCriteria sc;
    sc.energy_ratio = spec.settle_energy_ratio;
    sc.max_time_s = spec.max_time_s;
    sc.check_interval_s = 0.005;
    st = run_until_settled(sim, sc);
  }
  res.run.stop_reason = sim.failure().status != RunStatus::ok
                            ? std::string("guard: ") + to_string(sim.failure().status)
                            : st.reason;
  // Strike off at the rim by centroid.
  const BodyState& B = sim.bodies();
  for (std::size_t b = 0; b < B.size(); ++b) {
    if (B.position_m[b].z() < c.z()) {
      ++res.seeds_inside;
      res.mass_inside_kg += B.mass_kg[b];
    }
    res.centres.push_back(B.position_m[b]);
  }
  const double volume = c.x() * c.y() * c.z();
  res.bulk_density_kg_m3 = res.mass_inside_kg / volume;
  res.solid_fraction = res.bulk_density_kg_m3 / rho;
  res.spheres = body_spheres(sim);
  finish_report(res.run, sim, cpu0, wall_t0);
  return res;
}

}  // namespace seedcal
