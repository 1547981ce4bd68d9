// The spatial sort (sim/spatial_sort.cpp): with T threads the bodies are cut into T slabs across
// the longest side of their bounding box that is not along gravity, each a thread's share of the
// body pass, with equal sphere counts (a two-sphere clump counts twice); one thread keeps the
// Morton curve alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "solver/clump/mass_properties.hpp"
#include "solver/sim/work_split.hpp"
#include "tests/support/worlds.hpp"

namespace seedcal {
namespace {

constexpr double kSpacing = 0.003;  // lattice spacing, m: the 1 mm spheres do not touch

// An nx x ny x nz lattice of lone spheres (20 x 8 x 4 unless given), added in a shuffled order;
// every `clump_every`-th body is a clump of two spheres along z instead. Without gravity nothing
// moves; with it, one step moves nothing measurable either (a 1e-7 s step).
Simulation lattice(int threads, int clump_every, int nx = 20, int ny = 8, int nz = 4,
                   const Vec3& gravity = Vec3::Zero()) {
  testing::MaterialSpec m;
  SimulationOptions opt;
  opt.dt_s = 1e-7;
  opt.gravity_m_s2 = gravity;
  opt.threads = threads;
  opt.sort_interval_steps = 1;
  Simulation sim(testing::make_table(m), opt);
  std::vector<Vec3> at;
  for (int x = 0; x < nx; ++x)
    for (int y = 0; y < ny; ++y)
      for (int z = 0; z < nz; ++z) at.emplace_back(kSpacing * x, kSpacing * y, kSpacing * z);
  std::mt19937_64 rng(7);
  std::shuffle(at.begin(), at.end(), rng);
  for (std::size_t k = 0; k < at.size(); ++k) {
    const bool clump = clump_every > 0 && k % static_cast<std::size_t>(clump_every) == 0;
    BodyDef b = clump ? clump_body({{Vec3(0, 0, -0.0005), 0.001}, {Vec3(0, 0, 0.0005), 0.001}}, m.density_kg_m3, 0)
                      : sphere_body(0.001, m.density_kg_m3, 0);
    b.position_m = at[k];
    sim.add_body(b);
  }
  return sim;
}

// The body pass's shares after one step (which sorts) and the x and z ranges of each.
struct Share {
  double x_min = 1e9, x_max = -1e9, z_min = 1e9, z_max = -1e9;
  std::size_t spheres = 0;
};

std::vector<Share> shares_after_sort(Simulation& sim, int threads) {
  EXPECT_TRUE(sim.run(1)) << sim.failure().message;
  const BodyState& bodies = sim.bodies();
  std::vector<WorkShare> work(static_cast<std::size_t>(threads));
  split_bodies_by_spheres(bodies.first_sphere, bodies.size(), work);
  std::vector<Share> out(work.size());
  for (std::size_t t = 0; t < work.size(); ++t)
    for (std::size_t b = work[t].move_begin; b < work[t].move_end; ++b) {
      out[t].x_min = std::min(out[t].x_min, bodies.position_m[b].x());
      out[t].x_max = std::max(out[t].x_max, bodies.position_m[b].x());
      out[t].z_min = std::min(out[t].z_min, bodies.position_m[b].z());
      out[t].z_max = std::max(out[t].z_max, bodies.position_m[b].z());
      out[t].spheres += bodies.first_sphere[b + 1] - bodies.first_sphere[b];
    }
  return out;
}

TEST(SpatialSort, TwoThreadsGetTwoSlabsAcrossTheLongestSide) {
  Simulation sim = lattice(2, 0);
  const std::vector<Share> s = shares_after_sort(sim, 2);
  // 640 spheres, 320 a thread: columns x = 0-9 and 10-19 of the lattice.
  for (std::size_t t = 0; t < 2; ++t) {
    EXPECT_EQ(s[t].spheres, 320u) << t;
    EXPECT_NEAR(s[t].x_min, kSpacing * 10.0 * static_cast<double>(t), 1e-12) << t;
    EXPECT_NEAR(s[t].x_max, kSpacing * (10.0 * static_cast<double>(t) + 9.0), 1e-12) << t;
  }
}

TEST(SpatialSort, SlabsHoldEqualSphereCountsWithClumps) {
  // Every fourth body a two-sphere clump: 640 bodies, 800 spheres, 400 a thread.
  Simulation sim = lattice(2, 4);
  const std::vector<Share> s = shares_after_sort(sim, 2);
  EXPECT_LE(s[0].x_max, s[1].x_min);  // one plane between the threads' bodies
  EXPECT_NEAR(static_cast<double>(s[0].spheres), 400.0, 1.0);
  EXPECT_NEAR(static_cast<double>(s[1].spheres), 400.0, 1.0);
}

TEST(SpatialSort, ATallColumnIsCutAlongItsHeightUnlessGravityPointsThere) {
  // 8 x 6 x 20: the longest side is z. Without gravity the two slabs lie one above the other; with
  // gravity along -z the cut runs down the height (across x, the longer of the level sides), so
  // each thread gets half of the column's bottom, where a pour's contacts are.
  {
    Simulation sim = lattice(2, 0, 8, 6, 20);
    const std::vector<Share> s = shares_after_sort(sim, 2);
    EXPECT_LE(s[0].z_max, s[1].z_min);
    EXPECT_LT(s[0].x_min, s[1].x_max);
  }
  {
    Simulation sim = lattice(2, 0, 8, 6, 20, Vec3(0.0, 0.0, -9.81));
    const std::vector<Share> s = shares_after_sort(sim, 2);
    EXPECT_LT(s[0].x_max, s[1].x_min);
    EXPECT_NEAR(s[0].z_min, s[1].z_min, 1e-9);
    EXPECT_NEAR(s[0].z_max, s[1].z_max, 1e-9);
  }
}

TEST(SpatialSort, OneThreadKeepsTheCurveAlone) {
  // Halves of a one-thread run's order are not slabs: the curve's cells are 2 mm (a sphere's
  // diameter) and the columns 3 mm apart, so its first cut (cell 16) falls at column 11 of 20,
  // and its first half reaches past the second half's lowest column.
  Simulation sim = lattice(1, 0);
  const std::vector<Share> s = shares_after_sort(sim, 2);
  EXPECT_GT(s[0].x_max, s[1].x_min);
}

}  // namespace
}  // namespace seedcal
