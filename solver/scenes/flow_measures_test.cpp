// The custom scene's measurements (flow_measures.hpp) on hand-built cases of known answer: the mass
// of known bodies in a box, bodies crossing a plane at a known velocity (the discharge rate is their
// mass flux), and the surface of a known bed of spheres.
#include <gtest/gtest.h>

#include <cmath>

#include "solver/scenes/flow_measures.hpp"

namespace seedcal {
namespace {

TEST(FlowMeasures, MassInBoxCountsTheCentresInside) {
  const BoxRegion box{Vec3(0, 0, 0), Vec3(1, 1, 1)};
  const std::vector<Vec3> c = {{0.5, 0.5, 0.5}, {1.5, 0.5, 0.5}, {0.0, 1.0, 0.2}, {0.5, 0.5, -0.01}};
  const std::vector<double> m = {1.0, 2.0, 4.0, 8.0};
  // Inside: the first, and the third on the box's boundary (closed); not the second and the fourth.
  EXPECT_DOUBLE_EQ(mass_in_box(c, m, box), 5.0);
}

// A column of bodies of mass m, spaced s apart along z, falls at speed v through the plane z = 0
// (normal -z): the mass flux is m v / s. Sampled every dt, each update sees the bodies that
// crossed since the last; the steady rate is exactly m v / s wherever the window holds whole
// crossings at the sampled times (the cumulative mass is a step function, fitted by a line).
TEST(FlowMeasures, BodiesMovingAtAKnownVelocityGiveTheirMassFlux) {
  const double m = 0.5e-3, s = 0.01, v = 2.0;
  const std::size_t n = 200;
  PlaneCrossing plane(Vec3::Zero(), -Vec3::UnitZ());
  std::vector<std::uint32_t> ids(n);
  std::vector<double> masses(n, m);
  for (std::uint32_t i = 0; i < n; ++i) ids[i] = i;
  std::vector<double> t, cum;
  const double dt = 0.001;  // a body crosses every s / v = 5 ms: 5 samples per crossing
  for (int k = 0; k <= 800; ++k) {
    const double time = k * dt;
    std::vector<Vec3> c(n);
    // Body i starts at z = (i + 0.5) s and falls at v.
    for (std::size_t i = 0; i < n; ++i) c[i] = Vec3(0.0, 0.0, (static_cast<double>(i) + 0.5) * s - v * time);
    plane.update(ids, c, masses);
    t.push_back(time);
    cum.push_back(plane.crossed_kg());
  }
  // At t = 0.8 s, 1.6 m of the column has passed: 160 bodies.
  EXPECT_NEAR(plane.crossed_kg(), 160 * m, 1e-12);
  const SteadyRate r = steady_rate(t, cum, 0.2, 0.8);
  ASSERT_TRUE(r.ok);
  // The staircase's slope is m v / s = 0.1 kg/s; a line through a staircase of 96 steps differs
  // from it by under a step's height over the window's length (m / 0.48 s = 0.2 %).
  EXPECT_NEAR(r.rate_kg_s, m * v / s, 0.002 * m * v / s);
  EXPECT_GT(r.fit.r2, 0.999);
  EXPECT_NEAR(r.t_begin_s, 0.2 * 0.8, 0.01);
  EXPECT_NEAR(r.t_end_s, 0.8 * 0.8, 0.01);
}

TEST(FlowMeasures, ACrossingBackTakesTheMassOffAndNewBodiesOnlyRecordTheirSide) {
  PlaneCrossing plane(Vec3(0, 0, 1.0), Vec3::UnitX());
  plane.update({7}, {Vec3(-1, 0, 0)}, {2.0});
  EXPECT_EQ(plane.crossed_kg(), 0.0);
  plane.update({7, 8}, {Vec3(1, 0, 0), Vec3(5, 0, 0)}, {2.0, 3.0});  // 7 crossed; 8 is new
  EXPECT_EQ(plane.crossed_kg(), 2.0);
  plane.update({7, 8}, {Vec3(-1, 0, 0), Vec3(5, 0, 0)}, {2.0, 3.0});  // 7 back
  EXPECT_EQ(plane.crossed_kg(), 0.0);
  plane.update({8}, {Vec3(5, 0, 0)}, {3.0});  // 7 removed: forgotten
  plane.update({7}, {Vec3(1, 0, 0)}, {2.0});  // seen again: a new body
  EXPECT_EQ(plane.crossed_kg(), 0.0);
}

TEST(FlowMeasures, NoSteadyRateWithoutThreeSamplesInTheWindow) {
  EXPECT_FALSE(steady_rate({0.0, 1.0}, {0.0, 1.0}, 0.2, 0.8).ok);
  EXPECT_FALSE(steady_rate({0.0, 1.0, 2.0}, {0.0, 0.0, 0.0}, 0.2, 0.8).ok);
}

// A bed of spheres of radius r on a square lattice of pitch 2r, one layer from z = 0, the middle
// third two layers deep. A probe of radius 0 on a sphere's centre line meets its top (2r, or 4r in
// the middle); half a radius off the centre line it meets the sphere at r + r sqrt(3) / 2; a probe
// of radius r there reaches over to the top.
TEST(FlowMeasures, SurfaceHeightOfAKnownBed) {
  const double r = 0.004;
  std::vector<std::pair<Vec3, double>> spheres;
  for (int i = 0; i < 15; ++i)
    for (int j = -2; j <= 2; ++j) {
      spheres.push_back({Vec3((2 * i + 1) * r, 2 * j * r, r), r});
      if (i >= 5 && i < 10) spheres.push_back({Vec3((2 * i + 1) * r, 2 * j * r, 3 * r), r});
    }
  const std::vector<Vec3> pts = {Vec3(r, 0, 0), Vec3(15 * r, 0, 0), Vec3(1.5 * r, 0, 0), Vec3(100 * r, 0, 0)};
  const std::vector<double> h = surface_heights(spheres, pts, 0.0, 0.0);
  EXPECT_NEAR(h[0], 2 * r, 1e-15);  // on a one-layer column's centre: its top
  EXPECT_NEAR(h[1], 4 * r, 1e-15);  // in the two-layer middle
  EXPECT_NEAR(h[2], r + r * std::sqrt(3.0) / 2.0, 1e-15);
  EXPECT_EQ(h[3], 0.0);             // beyond the bed
  const std::vector<double> wide = surface_heights(spheres, pts, 0.0, r);
  EXPECT_NEAR(wide[2], 2 * r, 1e-15);
  // Measured from a line at z = r: heights less r.
  EXPECT_NEAR(surface_heights(spheres, pts, r, 0.0)[1], 3 * r, 1e-15);
}

}  // namespace
}  // namespace seedcal
