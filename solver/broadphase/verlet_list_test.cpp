// The Verlet list holds exactly the sphere pairs of different bodies within the skin (against a
// brute-force search), in (body i, body j, sphere i, sphere j) order, whichever way the candidates
// are found (one grid of spheres, or bodies first, then the spheres near the other body) and on
// any thread count; history survives a rebuild.
#include "solver/broadphase/verlet_list.hpp"

#include <random>
#include <tuple>

#include <gtest/gtest.h>

namespace seedcal {
namespace {

// `bodies` clumps of `per_body` spheres (radii 0.3 to 2 mm, one large central sphere of 3 mm
// as in the automatic fills) scattered in a 30 mm box, overlapping freely; body `gap` has none
// (as after a removal).
SphereState scattered_clumps(int bodies, int per_body, std::uint32_t gap, std::uint32_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  SphereState s;
  for (int b = 0; b < bodies; ++b) {
    if (static_cast<std::uint32_t>(b) == gap) continue;
    const Vec3 c(0.03 * u(rng), 0.03 * u(rng), 0.03 * u(rng));
    for (int k = 0; k < per_body; ++k) {
      const double r = k == 0 ? 0.003 : 0.0003 + 0.0017 * u(rng);
      const Vec3 off = k == 0 ? Vec3(Vec3::Zero()) : Vec3(Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5) * 0.008);
      s.body.push_back(static_cast<std::uint32_t>(b));
      s.offset_body_m.push_back(off);
      s.radius_m.push_back(r);
      s.material.push_back(0);
      s.position_m.push_back(c + off);
    }
  }
  return s;
}

using Pairs = std::vector<std::tuple<std::uint32_t, std::uint32_t, std::uint32_t, std::uint32_t>>;

Pairs listed(const VerletList& v, const SphereState& s) {
  Pairs p;
  for (std::size_t k = 0; k < v.pair_count(); ++k)
    p.emplace_back(s.body[v.si()[k]], s.body[v.sj()[k]], v.si()[k], v.sj()[k]);
  return p;
}

Pairs brute_force(const SphereState& s, double skin) {
  Pairs p;
  for (std::uint32_t i = 0; i < s.size(); ++i)
    for (std::uint32_t j = 0; j < s.size(); ++j) {
      if (s.body[i] >= s.body[j]) continue;
      const double cut = s.radius_m[i] + s.radius_m[j] + skin;
      if ((s.position_m[j] - s.position_m[i]).squaredNorm() < cut * cut) p.emplace_back(s.body[i], s.body[j], i, j);
    }
  std::sort(p.begin(), p.end());
  return p;
}

TEST(VerletList, BothSearchesListExactlyThePairsWithinTheSkin) {
  const double skin = 0.0004;
  for (const int per_body : {1, 9, 60}) {
    const SphereState s = scattered_clumps(per_body == 1 ? 400 : 60, per_body, 7, 11u + static_cast<std::uint32_t>(per_body));
    const Pairs truth = brute_force(s, skin);
    ASSERT_FALSE(truth.empty());
    for (const PairSearch search : {PairSearch::sphere_grid, PairSearch::two_level, PairSearch::automatic})
      for (const int threads : {1, 3}) {
        VerletList v;
        v.set_search(search);
        v.build(s, skin, false, threads);
        EXPECT_EQ(listed(v, s), truth) << "spheres per body " << per_body << ", search " << static_cast<int>(search)
                                       << ", threads " << threads;
        // One group per body pair, in order.
        std::size_t groups = 0;
        for (std::size_t k = 0; k < truth.size(); ++k)
          if (k == 0 || std::get<1>(truth[k]) != std::get<1>(truth[k - 1]) || std::get<0>(truth[k]) != std::get<0>(truth[k - 1]))
            ++groups;
        EXPECT_EQ(v.group_count(), groups);
      }
  }
}

TEST(VerletList, HistoryOfAPairSurvivesARebuildEitherWay) {
  const double skin = 0.0004;
  SphereState s = scattered_clumps(60, 60, 1000, 5);
  for (const PairSearch search : {PairSearch::sphere_grid, PairSearch::two_level}) {
    VerletList v;
    v.set_search(search);
    v.build(s, skin, true, 1);
    ASSERT_GT(v.pair_count(), 10u);
    const std::size_t k = v.pair_count() / 2;
    const std::uint32_t i = v.si()[k], j = v.sj()[k];
    v.tangential()[k] = Vec3(1e-6, 2e-6, 3e-6);
    v.rolling()[k] = Vec3(4e-6, 0, 0);
    v.build(s, skin, true, 2);
    bool found = false;
    for (std::size_t m = 0; m < v.pair_count(); ++m)
      if (v.si()[m] == i && v.sj()[m] == j) {
        found = true;
        EXPECT_EQ(v.tangential()[m], Vec3(1e-6, 2e-6, 3e-6));
        EXPECT_EQ(v.rolling()[m], Vec3(4e-6, 0, 0));
        EXPECT_EQ(v.live()[m], 1);
      }
    EXPECT_TRUE(found);
  }
}

}  // namespace
}  // namespace seedcal
