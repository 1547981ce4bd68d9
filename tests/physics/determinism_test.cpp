// Determinism: the same seed and thread count give bit-identical results; 1 and 2 threads agree
// to round-off over a short run (force sums are reduced in a different order).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>

#include "solver/sim/pair_batch.hpp"
#include "tests/support/random_bed.hpp"

namespace seedcal {
namespace {

// Two seed materials (0, and 2 on every other sphere; the walls are 1): every sphere pair's
// constants come from the pair of its materials, as in a mixture of two varieties.
InteractionTable two_seed_table(const testing::MaterialSpec& m) {
  return InteractionTable({{"seed_a", m.density_kg_m3, m.youngs_modulus_pa, m.poisson_ratio},
                           {"wall", 7800.0, 2.0e11, 0.3},
                           {"seed_b", m.density_kg_m3, 2.0 * m.youngs_modulus_pa, 0.3}},
                          {{"aa", 0, 0, m.restitution, m.static_friction, m.rolling_friction},
                           {"aw", 0, 1, m.restitution, m.static_friction, m.rolling_friction},
                           {"bb", 2, 2, 0.6, 0.3, 0.02},
                           {"ab", 0, 2, 0.5, 0.4, 0.03},
                           {"bw", 2, 1, 0.5, 0.5, 0.04}});
}

std::vector<Vec3> run_bed(int threads, std::uint64_t seed, int steps, int simd_lanes = 8,
                          NormalModel normal = NormalModel::hertz_mindlin,
                          RollingModel rolling = RollingModel::cdt, bool two_seeds = false) {
  const testing::MaterialSpec m = testing::table6_seed();
  SimulationOptions opt;
  opt.threads = threads;
  opt.seed = seed;
  opt.dt_s = 2e-6;
  opt.contact.normal = normal;
  opt.contact.rolling = rolling;
  opt.simd_lanes = simd_lanes;
  Simulation sim(two_seeds ? two_seed_table(m) : testing::make_table(m), opt);
  testing::BedSpec bed;
  if (two_seeds) bed.second_material = 2;
  testing::add_random_bed(sim, bed, m.density_kg_m3);
  EXPECT_TRUE(sim.run(static_cast<std::uint64_t>(steps))) << sim.failure().message;
  if (steps >= 1000) {
    EXPECT_GT(sim.stats().sphere_contacts, 0u);  // the bed has settled into contact
  }
  // By body id: the spatial sort orders the bodies by thread count (sim/spatial_sort.cpp).
  const BodyState& bodies = sim.bodies();
  std::vector<Vec3> by_id(bodies.size());
  for (std::size_t b = 0; b < bodies.size(); ++b) by_id[bodies.id[b]] = bodies.position_m[b];
  return by_id;
}

TEST(Determinism, SameSeedAndThreadsIsBitIdentical) {
  for (int threads : {1, 2}) {
    const auto a = run_bed(threads, 42, 3000);
    const auto b = run_bed(threads, 42, 3000);
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec3)), 0) << threads << " threads";
  }
}

TEST(Determinism, OneAndTwoThreadsAgree) {
  const auto a = run_bed(1, 42, 3000);
  const auto b = run_bed(2, 42, 3000);
  double worst = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, (a[i] - b[i]).norm());
  std::printf("512 spheres, 3000 steps: max position difference 1 vs 2 threads %.3e m\n", worst);
  // 1e-9 m (5e-7 of a radius): summation-order round-off (1e-16 relative) grows through the
  // contacts over 3000 steps but stays many orders below any physical length.
  EXPECT_LT(worst, 1e-9);
}

// The sphere-sphere and sphere-wall kernels on eight (AVX-512F) and four (AVX2) lanes give the
// same bits as on one lane (sim/pair_batch.hpp): settling, sliding and resting contacts, with and
// without HMNR, with CDT and EPSD, spheres of one material (the constants broadcast) and of two
// (gathered pair by pair). A width the CPU does not run is skipped.
TEST(Determinism, WideAndOneLaneKernelsAreBitIdentical) {
  struct Case {
    NormalModel normal;
    RollingModel rolling;
    int threads;
    bool two_seeds = false;
  };
  int widths_run = 0;
  for (const int lanes : {4, 8}) {
    if (pair_batch_lanes_used(lanes) != lanes) continue;
    ++widths_run;
    for (const Case c : {Case{NormalModel::hertz_mindlin, RollingModel::cdt, 1},
                         Case{NormalModel::hmnr, RollingModel::none, 1},
                         Case{NormalModel::hmnr, RollingModel::epsd, 1},
                         Case{NormalModel::hertz_mindlin, RollingModel::cdt, 2},
                         Case{NormalModel::hertz_mindlin, RollingModel::cdt, 1, true},
                         Case{NormalModel::hmnr, RollingModel::epsd, 1, true}}) {
      const auto a = run_bed(c.threads, 7, 3000, lanes, c.normal, c.rolling, c.two_seeds);
      const auto b = run_bed(c.threads, 7, 3000, 1, c.normal, c.rolling, c.two_seeds);
      ASSERT_EQ(a.size(), b.size());
      EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec3)), 0)
          << lanes << " lanes, " << to_string(c.normal) << " + " << to_string(c.rolling) << ", "
          << c.threads << " threads" << (c.two_seeds ? ", two seed materials" : "");
    }
  }
  if (widths_run == 0) GTEST_SKIP() << "this CPU has neither AVX2 nor AVX-512F: only the one-lane kernel runs";
}

TEST(Determinism, DifferentSeedsDiffer) {
  const auto a = run_bed(1, 1, 10);
  const auto b = run_bed(1, 2, 10);
  EXPECT_NE(std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec3)), 0);
}

}  // namespace
}  // namespace seedcal
