// Whole steps of a bed of 4,096 lone spheres in a box (Table 6's seed contact, Hertz-Mindlin
// with CDT rolling friction, dt 1e-6 s), on one and two threads: sphere-steps per second. The
// bed starts on a jittered lattice at contact and has 2,000 steps to settle into its contacts
// before the timing; it keeps evolving under gravity while timed, as a running scene does. The
// same spheres as one bed or two, to measure the pairs across the threads' split. And the
// neighbour-list build (broadphase/verlet_list.hpp) alone on the same spheres.
#include <benchmark/benchmark.h>

#include "solver/broadphase/verlet_list.hpp"
#include "tests/support/random_bed.hpp"

namespace seedcal {
namespace {

testing::BedSpec lattice_bed() {
  testing::BedSpec b;
  b.nx = b.ny = b.nz = 16;
  b.radius_m = 0.002;
  b.spacing = 2.0;
  b.jitter = 0.02;
  b.speed_m_s = 0.01;
  return b;
}

SimulationOptions step_options(int threads) {
  SimulationOptions opt;
  opt.dt_s = 1e-6;
  opt.threads = threads;
  opt.contact.rolling = RollingModel::cdt;
  opt.seed = 1;
  opt.profile = true;
  return opt;
}

// 2,000 steps to settle, then one step per iteration; sphere-steps per second, and the
// microseconds a step in each phase (StepProfile) with the neighbour builds per 1,000 steps.
void time_steps(benchmark::State& state, Simulation& sim) {
  sim.run(2000);
  const StepProfile before = sim.profile();
  const std::size_t builds_before = sim.neighbour_builds();
  for (auto _ : state)
    if (!sim.step()) {
      state.SkipWithError(sim.failure().message.c_str());
      break;
    }
  const auto spheres = static_cast<std::int64_t>(sim.spheres().size());
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * spheres);
  state.counters["contacts_per_sphere"] =
      2.0 * static_cast<double>(sim.stats().sphere_contacts) / static_cast<double>(spheres);
  const double steps = static_cast<double>(state.iterations());
  const StepProfile& p = sim.profile();
  state.counters["integrate_us"] = 1e6 * (p.integrate_s - before.integrate_s) / steps;
  state.counters["contact_us"] = 1e6 * (p.contact_s - before.contact_s) / steps;
  state.counters["reduce_us"] = 1e6 * (p.reduce_s - before.reduce_s) / steps;
  state.counters["neighbour_us"] = 1e6 * (p.neighbour_s - before.neighbour_s) / steps;
  state.counters["builds_per_1000"] =
      1000.0 * static_cast<double>(sim.neighbour_builds() - builds_before) / steps;
}

void BM_Step(benchmark::State& state) {
  const testing::MaterialSpec m = testing::table6_seed();
  Simulation sim(testing::make_table(m, 2.0e10, 0.3), step_options(static_cast<int>(state.range(0))));
  testing::add_random_bed(sim, lattice_bed(), m.density_kg_m3);
  time_steps(state, sim);
}
BENCHMARK(BM_Step)->ArgName("threads")->Arg(1)->Arg(2)->UseRealTime()->MinTime(0.5);

// What the pairs across the threads' split cost: a 16 x 16 x 16 lattice on a floor, inserted as
// its two halves in y (no spatial sort), so that each of two threads takes one half; either the
// halves touch (one bed: a plane of 256 bodies on each side whose pairs cross between the
// threads) or they stand 0.2 m apart (two beds: no pair crosses). The body pass has the same work
// in both; the contacts differ a little (the apart halves have no neighbour to lean on). Compare
// each with its own one-thread run.
void BM_StepSplit(benchmark::State& state) {
  const bool apart = state.range(1) != 0;
  const testing::MaterialSpec m = testing::table6_seed();
  SimulationOptions opt = step_options(static_cast<int>(state.range(0)));
  opt.sort_interval_steps = 0;
  Simulation sim(testing::make_table(m, 2.0e10, 0.3), opt);
  testing::BedSpec half = lattice_bed();
  half.ny /= 2;
  const double pitch = half.spacing * half.radius_m;
  testing::add_lattice_spheres(sim, half, m.density_kg_m3);
  testing::add_lattice_spheres(sim, half, m.density_kg_m3,
                               Vec3(0.0, half.ny * pitch + (apart ? 0.2 : 0.0), 0.0));
  sim.add_wall(testing::plane_wall(Vec3::Zero(), Vec3::UnitZ()));
  time_steps(state, sim);
}
BENCHMARK(BM_StepSplit)
    ->ArgNames({"threads", "apart"})
    ->ArgsProduct({{1, 2}, {0, 1}})
    ->UseRealTime()
    ->MinTime(0.5);

void BM_VerletBuild(benchmark::State& state) {
  const testing::MaterialSpec m = testing::table6_seed();
  SimulationOptions opt;
  opt.dt_s = 1e-6;
  Simulation sim(testing::make_table(m), opt);
  testing::add_random_bed(sim, lattice_bed(), m.density_kg_m3);
  sim.run(1);  // places the spheres
  const SphereState& spheres = sim.spheres();
  VerletList list;
  for (auto _ : state) {
    list.build(spheres, 0.4e-3, false, static_cast<int>(state.range(0)));
    benchmark::DoNotOptimize(list.pair_count());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(spheres.size()));
  state.counters["pairs"] = static_cast<double>(list.pair_count());
}
BENCHMARK(BM_VerletBuild)->ArgName("threads")->Arg(1)->Arg(2)->UseRealTime();

}  // namespace
}  // namespace seedcal
