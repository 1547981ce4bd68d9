// The piling scene's heap measurement (measure_heap) on synthetic heaps of known angle: a cone of
// spheres whose tops lie on or below the surface z = H - r tan(alpha), with and without a skirt of
// single spheres lying on the plate around its foot (seeds that ran out alone).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

#include "solver/scenes/piling.hpp"

namespace seedcal {
namespace {

constexpr double kRs = 0.0045;    // sphere radius, m
constexpr double kSeed = 2 * kRs;  // seed size

struct Heap {
  std::vector<std::pair<Vec3, double>> spheres;
  std::vector<Vec3> centres;
};

// Random sphere centres filling the cone (tops at or below its surface), dense enough that every
// half-seed column of every strip holds spheres whose tops reach near the surface. A skirt of
// `skirt` spheres lies on the plate (centre at z = r) between the cone's foot and 40 mm outward.
Heap cone(double alpha_deg, double height_m, int skirt, std::uint32_t seed = 1) {
  const double t = std::tan(alpha_deg * std::numbers::pi / 180.0);
  const double R = height_m / t;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Heap h;
  const int n = static_cast<int>(1e8 * R * R * height_m) + 2000;
  for (int k = 0; k < n; ++k) {
    const double r = R * std::sqrt(u(rng)), phi = 2.0 * std::numbers::pi * u(rng);
    const double top = height_m - r * t;  // surface height at r
    if (top < 2.0 * kRs) continue;
    const double z = kRs + (top - 2.0 * kRs) * std::sqrt(u(rng));  // denser near the surface
    const Vec3 c(r * std::cos(phi), r * std::sin(phi), z);
    h.spheres.push_back({c, kRs});
    h.centres.push_back(c);
  }
  for (int k = 0; k < skirt; ++k) {
    const double r = R - 2.0 * kRs / t + 0.04 * u(rng), phi = 2.0 * std::numbers::pi * u(rng);
    const Vec3 c(r * std::cos(phi), r * std::sin(phi), kRs);
    h.spheres.push_back({c, kRs});
    h.centres.push_back(c);
  }
  return h;
}

double measured(const Heap& h) {
  const HeapMeasurement m = measure_heap(h.spheres, h.centres, kSeed, 8, 0.2, 0.8);
  EXPECT_EQ(m.sector_angles_deg.size(), 8u);
  return m.angle_deg;
}

TEST(PilingMeasure, ConeOfKnownAngle) {
  for (double alpha : {25.0, 32.0, 40.0}) {
    const double a = measured(cone(alpha, 0.08, 0));
    std::printf("cone %.0f deg, 80 mm high: measured %.2f deg\n", alpha, a);
    EXPECT_NEAR(a, alpha, 1.0);
  }
}

TEST(PilingMeasure, SkirtOfRunOutSeedsIsNotTheHeapSide) {
  // A small heap (3.5 seeds high, as the quick rig's): the window's lower bound 0.2 h is below the
  // top of one seed lying on the plate, so without the foot the skirt would enter the fit and
  // flatten it (measured without the foot: 11.9 and 14.0 deg for these 25 and 32 deg cones).
  for (double alpha : {25.0, 32.0}) {
    const double a = measured(cone(alpha, 0.032, 400));
    std::printf("cone %.0f deg, 32 mm high, skirt: measured %.2f deg\n", alpha, a);
    EXPECT_NEAR(a, alpha, 2.0);
  }
  // A tall heap is unaffected by a skirt.
  EXPECT_NEAR(measured(cone(32.0, 0.08, 400)), 32.0, 1.0);
}

}  // namespace
}  // namespace seedcal
