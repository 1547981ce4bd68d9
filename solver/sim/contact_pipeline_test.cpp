// The pair kernel's short cuts (sim/pair_batch.hpp): the broadcast of one material pair's
// constants (PairBatchArgs::uniform_constants; the lists say when every sphere is of one material)
// gives the bits the lane-by-lane gather gives, and the pair and wall kernels that skip the end
// velocities where they equal the half-step ones (PairBatchArgs::end_velocities,
// WallBatchArgs::end_velocities) give the bits of those that read them.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

#include "solver/core/materials.hpp"
#include "solver/sim/contact_forces.hpp"
#include "solver/sim/contact_pipeline.hpp"
#include "solver/sim/pair_batch.hpp"
#include "solver/walls/wall.hpp"

namespace seedcal {
namespace {

// A jittered 4 x 4 x 4 lattice of lone spheres pressed on their neighbours (pitch 1.98 radii),
// of material 0, or of `second` on every other sphere when it is nonzero.
SphereState lattice(std::uint16_t second) {
  constexpr double r = 0.002;
  SphereState s;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i) {
        s.body.push_back(static_cast<std::uint32_t>(s.size()));
        s.offset_body_m.push_back(Vec3::Zero());
        s.radius_m.push_back(r);
        s.material.push_back(second != 0 && (i + j + k) % 2 == 1 ? second : 0);
        s.position_m.push_back(Vec3(i, j, k) * 1.98 * r + 0.01 * r * Vec3(u(rng), u(rng), u(rng)));
      }
  return s;
}

// A body moving and spinning at random, its end velocities equal to the half-step ones (as
// without ContactOptions::dashpot_predicted).
BodyView moving_body(std::mt19937_64& rng, const Vec3& position) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  BodyView b;
  b.velocity_m_s = 0.01 * Vec3(u(rng), u(rng), u(rng));
  b.angular_velocity = Vec3(u(rng), u(rng), u(rng));
  b.velocity_end_m_s = b.velocity_m_s;
  b.angular_velocity_end = b.angular_velocity;
  b.inv_mass = 1.0 / 4.5e-5;
  b.position_m = position;
  return b;
}

// A seed and a steel wall: material pair (0, 0) at index 0 of the packed constants, (0, 1) at 1,
// with other values.
std::vector<BatchPairConstants> seed_and_steel_constants() {
  const InteractionTable table({{"seed", 1340.0, 1.65e8, 0.4}, {"steel", 7800.0, 2.0e11, 0.3}},
                               {{"ss", 0, 0, 0.45, 0.55, 0.05}, {"sw", 0, 1, 0.6, 0.3, 0.02}});
  return pack_batch_constants(table);
}

TEST(ContactPipeline, ListsSayWhetherEverySphereIsOfOneMaterial) {
  ContactPipeline one;
  one.skin_m = 0.0004;
  one.rebuild(lattice(0), {}, false, 1);
  EXPECT_EQ(one.one_sphere_material, 0);
  ContactPipeline two;
  two.skin_m = 0.0004;
  two.rebuild(lattice(2), {}, false, 1);
  EXPECT_EQ(two.one_sphere_material, -1);
  // Lists rebuilt after the spheres changed follow them.
  two.rebuild(lattice(0), {}, false, 1);
  EXPECT_EQ(two.one_sphere_material, 0);
}

// The touching pairs of the lattice through the kernel of each width this CPU runs, the constants
// gathered from a two-material table and broadcast, the end velocities read and skipped (they
// equal the half-step ones here, as without ContactOptions::dashpot_predicted), under CDT and
// EPSD: the same forces, torques and springs, bit for bit.
TEST(ContactPipeline, ShortCutsGiveTheBitsOfTheFullKernel) {
  const SphereState s = lattice(0);
  ContactPipeline pipe;
  pipe.skin_m = 0.0004;
  pipe.rebuild(s, {}, false, 1);
  std::vector<SphereView> spheres(s.size());
  std::vector<BodyView> bodies(s.size());
  std::mt19937_64 rng(9);
  for (std::size_t i = 0; i < s.size(); ++i) {
    spheres[i].position_m = s.position_m[i];
    spheres[i].radius_m = s.radius_m[i];
    bodies[i] = moving_body(rng, s.position_m[i]);
  }
  std::vector<std::uint32_t> touching;
  for (std::uint32_t k = 0; k < pipe.pairs.pair_count(); ++k) {
    const std::uint32_t i = pipe.pairs.si()[k], j = pipe.pairs.sj()[k];
    const double rs = s.radius_m[i] + s.radius_m[j];
    if ((s.position_m[j] - s.position_m[i]).squaredNorm() < rs * rs) touching.push_back(k);
  }
  ASSERT_GT(touching.size(), 100u);
  const std::vector<BatchPairConstants> constants = seed_and_steel_constants();
  const std::vector<double> mass(s.size(), 4.5e-5);
  const std::vector<Vec3> inertia(s.size(), Vec3::Constant(7.2e-11));
  struct Out {
    std::vector<BodyAccumulator> acc;
    std::vector<Vec3> springs, rolling;
  };
  const auto run = [&](int lanes, RollingModel rolling, bool broadcast, bool end_velocities) {
    Out o;
    // Every byte zero: the record's Eigen members are not zeroed by {}, and it has padding.
    o.acc.resize(s.size());
    std::memset(static_cast<void*>(o.acc.data()), 0, o.acc.size() * sizeof(BodyAccumulator));
    o.springs.assign(pipe.pairs.pair_count(), Vec3::Zero());
    o.rolling.assign(pipe.pairs.pair_count(), Vec3::Zero());
    std::vector<std::uint8_t> touched(s.size(), 0);
    PairBatchArgs a;
    a.spheres = reinterpret_cast<const double*>(spheres.data());
    a.sphere_body = s.body.data();
    a.sphere_material = s.material.data();
    a.bodies = reinterpret_cast<const double*>(bodies.data());
    a.accumulators = reinterpret_cast<double*>(o.acc.data());
    a.touched = touched.data();
    a.pair_constants = constants.data();
    a.materials = 2;
    a.uniform_constants = broadcast ? &constants[0] : nullptr;
    a.si = pipe.pairs.si().data();
    a.sj = pipe.pairs.sj().data();
    a.tangential_m = o.springs.data()->data();
    a.rolling_m = o.rolling.data()->data();
    a.body_mass_kg = mass.data();
    a.body_inertia_kg_m2 = inertia.data()->data();
    a.epsd_damping_ratio = 0.3;
    a.dt_s = 1e-6;
    a.rolling = rolling;
    a.end_velocities = end_velocities;
    PairBatchStats stats;
    // Two passes: the second starts from the springs the first wrote.
    for (int pass = 0; pass < 2; ++pass)
      choose_pair_batch(lanes)(a, touching.data(), nullptr, touching.size(), stats);
    return o;
  };
  const auto same = [](const Out& x, const Out& y) {
    return std::memcmp(x.acc.data(), y.acc.data(), x.acc.size() * sizeof(BodyAccumulator)) == 0 &&
           std::memcmp(x.springs.data(), y.springs.data(), x.springs.size() * sizeof(Vec3)) == 0 &&
           std::memcmp(x.rolling.data(), y.rolling.data(), x.rolling.size() * sizeof(Vec3)) == 0;
  };
  for (const RollingModel rolling : {RollingModel::cdt, RollingModel::epsd})
    for (const int lanes : {1, 4, 8}) {
      if (pair_batch_lanes_used(lanes) != lanes) continue;
      const Out full = run(lanes, rolling, false, true);
      EXPECT_TRUE(same(full, run(lanes, rolling, true, true))) << lanes << " lanes, broadcast";
      EXPECT_TRUE(same(full, run(lanes, rolling, false, false))) << lanes << " lanes, no end velocities";
      EXPECT_TRUE(same(full, run(lanes, rolling, true, false))) << lanes << " lanes, both";
    }
}

// Sphere-wall contacts of moving, spinning bodies on a moving wall through the wall kernel of each
// width, the end velocities read and skipped: the same results and springs, bit for bit.
TEST(ContactPipeline, WallKernelWithoutEndVelocitiesGivesTheSameBits) {
  constexpr std::size_t n = 13;  // not a multiple of the lanes: the last batch is partial
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<BodyView> bodies(n);
  std::vector<WallContactIn> in(n);
  std::vector<WallRollingIn> rolling_in(n);
  std::vector<double> scale(n, 1.0);
  for (std::size_t i = 0; i < n; ++i) {
    bodies[i] = moving_body(rng, Vec3(u(rng), u(rng), u(rng)));
    const Vec3 normal = Vec3(0.1 * u(rng), 0.1 * u(rng), -1.0).normalized();
    WallContactIn& c = in[i];
    for (int k = 0; k < 3; ++k) {
      c.normal[k] = normal[k];
      c.lever_m[k] = 0.002 * normal[k];
      c.wall_velocity_m_s[k] = 0.005 * u(rng);
    }
    c.overlap_m = 2e-6 * (1.5 + u(rng));
    c.radius_m = 0.002;
    c.mass_kg = 4.5e-5;
    c.rolling_lever_m = 0.002;
    c.spare = 0.0;
    c.body = static_cast<std::uint32_t>(i);
    c.constants = 1;
    c.pair = i;
    rolling_in[i] = {{0.0, 0.0, 0.5}, 7.2e-11 + 4.5e-5 * 4e-6};
  }
  const std::vector<BatchPairConstants> constants = seed_and_steel_constants();
  struct Out {
    std::vector<WallContactOut> out;
    std::vector<Vec3> springs, rolling;
  };
  const auto run = [&](int lanes, RollingModel rolling, bool end_velocities) {
    Out o;
    o.out.resize(n);
    std::memset(static_cast<void*>(o.out.data()), 0, n * sizeof(WallContactOut));
    o.springs.assign(n, Vec3::Zero());
    o.rolling.assign(n, Vec3::Zero());
    WallBatchArgs a;
    a.bodies = reinterpret_cast<const double*>(bodies.data());
    a.pair_constants = constants.data();
    a.tangential_m = o.springs.data()->data();
    a.rolling_m = o.rolling.data()->data();
    a.dt_s = 1e-6;
    a.rolling = rolling;
    a.epsd_damping_ratio = 0.3;
    a.end_velocities = end_velocities;
    for (int pass = 0; pass < 2; ++pass)
      choose_wall_batch(lanes)(a, WallBatch{in.data(), scale.data(), rolling_in.data(), n, o.out.data()});
    return o;
  };
  for (const RollingModel rolling : {RollingModel::cdt, RollingModel::epsd})
    for (const int lanes : {1, 4, 8}) {
      if (pair_batch_lanes_used(lanes) != lanes) continue;
      const Out full = run(lanes, rolling, true), lean = run(lanes, rolling, false);
      EXPECT_EQ(std::memcmp(full.out.data(), lean.out.data(), n * sizeof(WallContactOut)), 0) << lanes;
      EXPECT_EQ(std::memcmp(full.springs.data(), lean.springs.data(), n * sizeof(Vec3)), 0) << lanes;
      EXPECT_EQ(std::memcmp(full.rolling.data(), lean.rolling.data(), n * sizeof(Vec3)), 0) << lanes;
      EXPECT_GT(full.springs[0].norm(), 0.0);  // the springs grew: the velocities were read
    }
}

}  // namespace
}  // namespace seedcal
