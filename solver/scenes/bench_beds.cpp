#include "solver/scenes/bench_beds.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <random>

#include "solver/broadphase/cell_grid.hpp"
#include "solver/sim/pair_batch.hpp"
#include "solver/sim/particle_factory.hpp"
#include "solver/sim/simulation.hpp"
#include "solver/sim/work_split.hpp"

namespace seedcal {
namespace {

Wall plane(const Vec3& point, const Vec3& normal) {
  Wall w;
  w.name = "plane";
  w.shape = std::make_shared<PlaneShape>(normal);
  w.material = 0;
  w.pose.origin_m = point;
  return w;
}

// Bodies with a touching sphere pair to a body of another thread's share of the body pass
// (equal sphere counts in index order, as the solver splits it), counted once after the timed
// steps. The candidate pairs come from a cell grid (broadphase/cell_grid.hpp) with cells of the
// largest sphere diameter: every touching pair lies in adjacent cells.
std::size_t bodies_across_threads(const Simulation& sim, int threads) {
  const BodyState& bodies = sim.bodies();
  const SphereState& spheres = sim.spheres();
  std::vector<WorkShare> shares(static_cast<std::size_t>(std::max(1, threads)));
  split_bodies_by_spheres(bodies.first_sphere, bodies.size(), shares);
  std::vector<std::uint32_t> owner(bodies.size());
  for (std::size_t t = 0; t < shares.size(); ++t)
    for (std::size_t b = shares[t].move_begin; b < shares[t].move_end; ++b)
      owner[b] = static_cast<std::uint32_t>(t);
  double r_max = 0.0;
  for (double r : spheres.radius_m) r_max = std::max(r_max, r);
  CellGrid grid;
  grid.build(spheres.position_m, 2.0 * r_max);
  std::vector<char> across(bodies.size(), 0);
  for (std::size_t i = 0; i < spheres.size(); ++i) {
    grid.for_each_near(spheres.position_m[i], [&](std::uint32_t j) {
      if (j <= i) return;
      const std::uint32_t bi = spheres.body[i], bj = spheres.body[j];
      if (owner[bi] == owner[bj]) return;
      const double rs = spheres.radius_m[i] + spheres.radius_m[j];
      if ((spheres.position_m[i] - spheres.position_m[j]).squaredNorm() < rs * rs) across[bi] = across[bj] = 1;
    });
  }
  return static_cast<std::size_t>(std::count(across.begin(), across.end(), 1));
}

}  // namespace

BenchSpec settled_bed_spec() {
  BenchSpec s;
  s.name = "settled-bed";
  s.settle_steps = 80000;
  return s;
}

BenchSpec clump_bed_spec(std::vector<SphereXYZR> clump) {
  BenchSpec s;
  s.name = "clump-bed";
  s.clump = std::move(clump);
  s.bodies = 1000;
  s.region_lo_m = Vec3(0.006, 0.006, 0.006);
  s.region_hi_m = Vec3(0.094, 0.094, 0.294);
  s.settle_steps = 100000;
  return s;
}

BenchSpec fine_clump_bed_spec(std::vector<SphereXYZR> clump) {
  BenchSpec s;
  s.name = "fine-clump-bed";
  s.clump = std::move(clump);
  s.bodies = 100;
  s.box_xy_m = 0.05;
  s.region_lo_m = Vec3(0.006, 0.006, 0.006);
  s.region_hi_m = Vec3(0.044, 0.044, 0.144);
  s.settle_dt_s = 2.5e-6;
  s.settle_steps = 160000;
  return s;
}

BenchResult run_bench(const BenchSpec& spec) {
  const bool clumps = !spec.clump.empty();
  const Material seed{"seed", 1340.0, 1.65e8, 0.4};
  const InteractionTable table({seed}, {Interaction{"seed_seed", 0, 0, 0.45, 0.55, 0.05}});
  SimulationOptions opt;
  opt.contact.normal = NormalModel::hertz_mindlin;
  opt.contact.rolling = RollingModel::cdt;
  opt.dt_s = spec.settle_dt_s;
  opt.skin_m = 0.0004;
  opt.profile = true;  // four clock reads per step: negligible against a 10,000-sphere step
  opt.threads = spec.threads;
  opt.seed = spec.seed;
  opt.simd_lanes = spec.simd_lanes;
  opt.pair_search = spec.pair_search;
  Simulation sim(table, opt);
  BodyDef tpl = clumps ? clump_body(spec.clump, seed.density_kg_m3, 0) : sphere_body(0.002, seed.density_kg_m3, 0);
  const Vec3 lo = spec.region_lo_m, hi = spec.region_hi_m;
  const std::size_t want = spec.bodies;
  const double side = spec.box_xy_m;
  BenchResult res;
  res.kernel_lanes = pair_batch_lanes_used(spec.simd_lanes);
  // As the decks' insert/pack: random non-overlapping poses, all inside the region.
  FactorySpec fs;
  fs.body = tpl;
  fs.region.lo_m = lo;
  fs.region.hi_m = hi;
  fs.count = want;
  fs.random_orientation = clumps;
  fs.max_attempts = 300 * want;
  const FactoryResult placed = insert_particles(sim, fs);
  if (!placed.complete) res.failure = placed.stop_reason;
  sim.add_wall(plane(Vec3::Zero(), Vec3::UnitZ()));
  sim.add_wall(plane(Vec3::Zero(), Vec3::UnitX()));
  sim.add_wall(plane(Vec3(side, 0, 0), -Vec3::UnitX()));
  sim.add_wall(plane(Vec3::Zero(), Vec3::UnitY()));
  sim.add_wall(plane(Vec3(0, side, 0), -Vec3::UnitY()));

  auto t0 = std::chrono::steady_clock::now();
  if (!sim.run(spec.settle_steps)) res.failure = sim.failure().message;
  res.settle_wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  sim.set_time_step(1e-6);
  const std::size_t builds0 = sim.neighbour_builds();
  const StepProfile p0 = sim.profile();
  t0 = std::chrono::steady_clock::now();
  if (res.failure.empty() && !sim.run(spec.timed_steps)) res.failure = sim.failure().message;
  res.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const StepProfile p1 = sim.profile();
  res.integrate_s = p1.integrate_s - p0.integrate_s;
  res.neighbour_s = p1.neighbour_s - p0.neighbour_s;
  res.contact_s = p1.contact_s - p0.contact_s;
  res.reduce_s = p1.reduce_s - p0.reduce_s;
  res.spheres = sim.spheres().size();
  res.bodies = sim.bodies().size();
  res.steps = spec.timed_steps;
  res.sphere_steps_per_second = static_cast<double>(res.spheres) * static_cast<double>(res.steps) / res.wall_seconds;
  res.contacts_per_sphere = (2.0 * static_cast<double>(sim.stats().sphere_contacts) +
                             static_cast<double>(sim.stats().wall_contacts)) / static_cast<double>(res.spheres);
  res.neighbour_builds = sim.neighbour_builds() - builds0;
  res.kinetic_energy_j = sim.kinetic_energy_j();
  res.bodies_across_threads = bodies_across_threads(sim, spec.threads);
  return res;
}

}  // namespace seedcal
