// The contact kernel's split of a step's work between threads (sim/work_split.hpp): every group
// goes to exactly one thread, a thread's sphere and wall groups belong to one range of bodies, the
// shares carry equal work to within one body's pairs, and one thread takes everything.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "solver/sim/work_split.hpp"

namespace seedcal {
namespace {

// A list with `pairs_of[b]` pairs for body b, in groups of at most `group_pairs` pairs.
struct TestList {
  std::vector<std::uint32_t> start{0};
  std::vector<std::uint32_t> body;
  TestList(const std::vector<int>& pairs_of, int group_pairs) {
    for (std::size_t b = 0; b < pairs_of.size(); ++b)
      for (int left = pairs_of[b]; left > 0; left -= group_pairs) {
        start.push_back(start.back() + static_cast<std::uint32_t>(std::min(left, group_pairs)));
        body.push_back(static_cast<std::uint32_t>(b));
      }
  }
  std::size_t groups() const { return body.size(); }
  GroupedList view() const {
    return {start, groups(), [this](std::size_t g) { return body[g]; }};
  }
};

double work(const TestList& s, const TestList& w, const WorkShare& sh) {
  return (s.start[sh.sphere_end] - s.start[sh.sphere_begin]) +
         kWallPairWeight * (w.start[sh.wall_end] - w.start[sh.wall_begin]);
}

TEST(WorkSplit, SharesCoverEveryGroupOnceByBodyRangesWithEqualWork) {
  std::mt19937 rng(7);
  const std::size_t bodies = 2000;
  std::vector<int> sphere_pairs(bodies), wall_pairs(bodies, 0);
  for (std::size_t b = 0; b < bodies; ++b) {
    sphere_pairs[b] = static_cast<int>(rng() % 40);
    // The first fifth of the bodies lie on the floor: their wall pairs load one end of the range.
    if (b < bodies / 5) wall_pairs[b] = 1 + static_cast<int>(rng() % 9);
  }
  const TestList s(sphere_pairs, 16), w(wall_pairs, 4);
  for (std::size_t threads : {1, 2, 3, 8}) {
    const auto shares = split_contact_work(s.view(), w.view(), bodies, threads);
    ASSERT_EQ(shares.size(), threads);
    EXPECT_EQ(shares.front().sphere_begin, 0u);
    EXPECT_EQ(shares.front().wall_begin, 0u);
    EXPECT_EQ(shares.back().sphere_end, s.groups());
    EXPECT_EQ(shares.back().wall_end, w.groups());
    double total = 0.0, largest_body = 0.0;
    for (std::size_t b = 0; b < bodies; ++b)
      largest_body = std::max(largest_body, sphere_pairs[b] + kWallPairWeight * wall_pairs[b]);
    for (const WorkShare& sh : shares) total += work(s, w, sh);
    EXPECT_EQ(total, s.start.back() + kWallPairWeight * w.start.back());
    for (std::size_t t = 0; t < threads; ++t) {
      const WorkShare& sh = shares[t];
      if (t > 0) {
        EXPECT_EQ(sh.sphere_begin, shares[t - 1].sphere_end);
        EXPECT_EQ(sh.wall_begin, shares[t - 1].wall_end);
      }
      // One body range: no body's groups on both sides of a cut, in either list.
      if (t > 0 && sh.sphere_begin > 0 && sh.sphere_begin < s.groups()) {
        EXPECT_LT(s.body[sh.sphere_begin - 1], s.body[sh.sphere_begin]);
      }
      if (t > 0 && sh.wall_begin > 0 && sh.wall_begin < w.groups()) {
        EXPECT_LT(w.body[sh.wall_begin - 1], w.body[sh.wall_begin]);
      }
      EXPECT_NEAR(work(s, w, sh), total / static_cast<double>(threads), largest_body)
          << threads << " threads, share " << t;
      // The share's body range holds exactly the bodies of its groups (the force reduction sums
      // the share's bodies), and the ranges tile [0, bodies).
      EXPECT_EQ(sh.body_begin, t == 0 ? 0u : shares[t - 1].body_end);
      EXPECT_LE(sh.body_begin, sh.body_end);
      for (std::size_t g = sh.sphere_begin; g < sh.sphere_end; ++g) {
        EXPECT_GE(s.body[g], sh.body_begin);
        EXPECT_LT(s.body[g], sh.body_end);
      }
      for (std::size_t g = sh.wall_begin; g < sh.wall_end; ++g) {
        EXPECT_GE(w.body[g], sh.body_begin);
        EXPECT_LT(w.body[g], sh.body_end);
      }
    }
    EXPECT_EQ(shares.back().body_end, bodies);
  }
}

TEST(WorkSplit, OneThreadTakesEverythingAndEmptyListsSplit) {
  const TestList s({3, 0, 5}, 2), w({}, 1);
  const auto one = split_contact_work(s.view(), w.view(), 3, 1);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].sphere_begin, 0u);
  EXPECT_EQ(one[0].sphere_end, s.groups());
  EXPECT_EQ(one[0].wall_end, 0u);
  const TestList none({0, 0}, 1);
  const auto empty = split_contact_work(none.view(), none.view(), 2, 4);
  ASSERT_EQ(empty.size(), 4u);
  for (const WorkShare& sh : empty) {
    EXPECT_EQ(sh.sphere_begin, sh.sphere_end);
    EXPECT_EQ(sh.wall_begin, sh.wall_end);
  }
}

TEST(WorkSplit, IntegratorRangesTileTheBodiesWithEqualSpheres) {
  // Lone spheres, then clumps of 9, then a few of 40: equal body counts would load the last
  // shares with most of the spheres.
  std::vector<std::uint32_t> first{0};
  std::size_t largest = 0;
  for (int b = 0; b < 1500; ++b) {
    const std::uint32_t n = b < 1000 ? 1u : (b < 1480 ? 9u : 40u);
    largest = std::max<std::size_t>(largest, n);
    first.push_back(first.back() + n);
  }
  const std::size_t bodies = first.size() - 1;
  for (std::size_t threads : {1, 2, 3, 8}) {
    std::vector<WorkShare> shares(threads);
    split_bodies_by_spheres(first, bodies, shares);
    EXPECT_EQ(shares.front().move_begin, 0u);
    EXPECT_EQ(shares.back().move_end, bodies);
    for (std::size_t t = 0; t < threads; ++t) {
      if (t > 0) {
        EXPECT_EQ(shares[t].move_begin, shares[t - 1].move_end);
      }
      const double spheres = first[shares[t].move_end] - first[shares[t].move_begin];
      EXPECT_NEAR(spheres, static_cast<double>(first.back()) / static_cast<double>(threads),
                  static_cast<double>(largest))
          << threads << " threads, share " << t;
    }
  }
  // No bodies: every range empty.
  std::vector<WorkShare> four(4);
  split_bodies_by_spheres({0}, 0, four);
  for (const WorkShare& sh : four) EXPECT_EQ(sh.move_begin, sh.move_end);
}

}  // namespace
}  // namespace seedcal
