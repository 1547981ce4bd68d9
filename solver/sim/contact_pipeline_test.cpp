// The pair kernel's broadcast of one material pair's constants (sim/pair_batch.hpp,
// PairBatchArgs::uniform_constants): the lists say when every sphere is of one material, and the
// broadcast gives the bits the lane-by-lane gather gives.
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
// gathered from a two-material table and broadcast: the same forces, torques and springs, bit for
// bit.
TEST(ContactPipeline, BroadcastConstantsGiveTheGatheredBits) {
  const SphereState s = lattice(0);
  ContactPipeline pipe;
  pipe.skin_m = 0.0004;
  pipe.rebuild(s, {}, false, 1);
  std::vector<SphereView> spheres(s.size());
  std::vector<BodyView> bodies(s.size());
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (std::size_t i = 0; i < s.size(); ++i) {
    spheres[i].position_m = s.position_m[i];
    spheres[i].radius_m = s.radius_m[i];
    bodies[i].velocity_m_s = 0.01 * Vec3(u(rng), u(rng), u(rng));
    bodies[i].angular_velocity = Vec3(u(rng), u(rng), u(rng));
    bodies[i].velocity_end_m_s = bodies[i].velocity_m_s;
    bodies[i].angular_velocity_end = bodies[i].angular_velocity;
    bodies[i].inv_mass = 1.0 / 4.5e-5;
    bodies[i].position_m = s.position_m[i];
  }
  std::vector<std::uint32_t> touching;
  for (std::uint32_t k = 0; k < pipe.pairs.pair_count(); ++k) {
    const std::uint32_t i = pipe.pairs.si()[k], j = pipe.pairs.sj()[k];
    const double rs = s.radius_m[i] + s.radius_m[j];
    if ((s.position_m[j] - s.position_m[i]).squaredNorm() < rs * rs) touching.push_back(k);
  }
  ASSERT_GT(touching.size(), 100u);
  // Material 0 against 0 sits at index 0 of a two-material table; the wall's row differs.
  const InteractionTable table({{"seed", 1340.0, 1.65e8, 0.4}, {"steel", 7800.0, 2.0e11, 0.3}},
                               {{"ss", 0, 0, 0.45, 0.55, 0.05}, {"sw", 0, 1, 0.6, 0.3, 0.02}});
  const std::vector<BatchPairConstants> constants = pack_batch_constants(table);
  struct Out {
    std::vector<BodyAccumulator> acc;
    std::vector<Vec3> springs;
  };
  const auto run = [&](int lanes, bool broadcast) {
    Out o;
    // Every byte zero: the record's Eigen members are not zeroed by {}, and it has padding.
    o.acc.resize(s.size());
    std::memset(static_cast<void*>(o.acc.data()), 0, o.acc.size() * sizeof(BodyAccumulator));
    o.springs.assign(pipe.pairs.pair_count(), Vec3::Zero());
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
    a.dt_s = 1e-6;
    a.rolling = RollingModel::cdt;
    PairBatchStats stats;
    // Two passes: the second starts from the springs the first wrote.
    for (int pass = 0; pass < 2; ++pass)
      choose_pair_batch(lanes)(a, touching.data(), nullptr, touching.size(), stats);
    return o;
  };
  for (const int lanes : {1, 4, 8}) {
    if (pair_batch_lanes_used(lanes) != lanes) continue;
    const Out gathered = run(lanes, false), broadcast = run(lanes, true);
    EXPECT_EQ(std::memcmp(gathered.acc.data(), broadcast.acc.data(),
                          gathered.acc.size() * sizeof(BodyAccumulator)), 0) << lanes << " lanes";
    EXPECT_EQ(std::memcmp(gathered.springs.data(), broadcast.springs.data(),
                          gathered.springs.size() * sizeof(Vec3)), 0) << lanes << " lanes";
  }
}

}  // namespace
}  // namespace seedcal
