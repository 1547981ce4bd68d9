// Whole steps of a bed of 4,096 lone spheres in a box (Table 6's seed contact, Hertz-Mindlin
// with CDT rolling friction, dt 1e-6 s), on one and two threads: sphere-steps per second. The
// bed starts on a jittered lattice at contact and has 2,000 steps to settle into its contacts
// before the timing; it keeps evolving under gravity while timed, as a running scene does. And the
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

void BM_Step(benchmark::State& state) {
  const testing::MaterialSpec m = testing::table6_seed();
  SimulationOptions opt;
  opt.dt_s = 1e-6;
  opt.threads = static_cast<int>(state.range(0));
  opt.contact.rolling = RollingModel::cdt;
  opt.seed = 1;
  opt.profile = true;
  Simulation sim(testing::make_table(m, 2.0e10, 0.3), opt);
  testing::add_random_bed(sim, lattice_bed(), m.density_kg_m3);
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
  // Microseconds a step in each phase (StepProfile), and neighbour builds per 1,000 steps.
  const double steps = static_cast<double>(state.iterations());
  const StepProfile& p = sim.profile();
  state.counters["integrate_us"] = 1e6 * (p.integrate_s - before.integrate_s) / steps;
  state.counters["contact_us"] = 1e6 * (p.contact_s - before.contact_s) / steps;
  state.counters["reduce_us"] = 1e6 * (p.reduce_s - before.reduce_s) / steps;
  state.counters["neighbour_us"] = 1e6 * (p.neighbour_s - before.neighbour_s) / steps;
  state.counters["builds_per_1000"] =
      1000.0 * static_cast<double>(sim.neighbour_builds() - builds_before) / steps;
}
BENCHMARK(BM_Step)->ArgName("threads")->Arg(1)->Arg(2)->UseRealTime()->MinTime(0.5);

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
