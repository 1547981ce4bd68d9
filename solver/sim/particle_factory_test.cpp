// The particle factory: non-overlapping, deterministic for a seed, the truncated-normal scale
// distribution, scaled mass properties, stop by count or mass, walls respected, the reason given.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "solver/sim/particle_factory.hpp"
#include "solver/walls/cylinder_shape.hpp"
#include "solver/walls/mesh_shape.hpp"
#include "tests/support/worlds.hpp"

namespace seedcal {
namespace {

// Brute force: no two spheres of different bodies overlap.
void expect_no_overlap(const Simulation& sim) {
  const auto& S = sim.spheres();
  for (std::size_t i = 0; i < S.size(); ++i)
    for (std::size_t j = i + 1; j < S.size(); ++j) {
      if (S.body[i] == S.body[j]) continue;
      ASSERT_GE((S.position_m[i] - S.position_m[j]).norm(), S.radius_m[i] + S.radius_m[j]) << i << " " << j;
    }
}

TEST(ParticleFactory, PlacesNonOverlappingBodiesDeterministically) {
  testing::MaterialSpec m;
  auto run = [&](std::uint64_t seed) {
    SimulationOptions opt;
    opt.dt_s = 1e-6;
    opt.seed = seed;
    Simulation sim(testing::make_table(m), opt);
    FactorySpec fs;
    fs.body = sphere_body(0.002, m.density_kg_m3, 0);
    fs.region.lo_m = Vec3::Zero();
    fs.region.hi_m = Vec3(0.04, 0.04, 0.04);
    fs.scale = {1.0, 0.1, 0.8, 1.2};
    fs.count = 500;
    const FactoryResult r = insert_particles(sim, fs);
    EXPECT_TRUE(r.complete) << r.stop_reason;
    EXPECT_EQ(r.placed, 500u);
    expect_no_overlap(sim);
    for (const Vec3& p : sim.spheres().position_m)  // inside the region
      EXPECT_TRUE((p.array() > 0.0).all() && (p.array() < 0.04).all());
    return sim.spheres().radius_m;
  };
  const auto a = run(5), b = run(5), c = run(6);
  EXPECT_EQ(a, b);  // bit-identical for one seed
  EXPECT_NE(a, c);
  double mean = 0.0, var = 0.0;
  for (double r : a) mean += r / 0.002;
  mean /= static_cast<double>(a.size());
  for (double r : a) var += (r / 0.002 - mean) * (r / 0.002 - mean);
  const double sd = std::sqrt(var / static_cast<double>(a.size() - 1));
  std::printf("factory: 500 scales, mean %.4f (expected 1), sd %.4f (expected 0.0880)\n", mean, sd);
  // Truncation at +-2 sd leaves the mean at 1 and shrinks the sd to 0.880 of 0.1 (truncated
  // normal: sd^2 (1 - 2 b phi(b) / (2 Phi(b) - 1)), b = 2). Mean: 5 standard errors
  // (0.088 / sqrt(500)); sd: its standard error is ~ sd / sqrt(2 n) = 0.0028, 0.015 is 5 of them.
  EXPECT_NEAR(mean, 1.0, 5 * 0.088 / std::sqrt(500.0));
  EXPECT_NEAR(sd, 0.088, 0.015);
  for (double r : a) EXPECT_TRUE(r >= 0.8 * 0.002 && r <= 1.2 * 0.002);
}

TEST(ParticleFactory, ScalesMassPropertiesAsVolumeAndInertia) {
  BodyDef d;
  d.spheres = {{Vec3(0.001, 0, 0), 0.002}, {Vec3(-0.001, 0, 0), 0.0015}};
  d.mass_kg = 2e-4;
  d.principal_inertia_kg_m2 = Vec3(1e-10, 2e-10, 3e-10);
  const BodyDef s = scaled_body(d, 1.5);
  EXPECT_DOUBLE_EQ(s.spheres[0].offset_m.x(), 0.0015);  // lengths x s
  EXPECT_DOUBLE_EQ(s.spheres[1].radius_m, 0.00225);
  EXPECT_DOUBLE_EQ(s.mass_kg, 2e-4 * 3.375);                                  // mass x s^3
  EXPECT_TRUE(s.principal_inertia_kg_m2.isApprox(d.principal_inertia_kg_m2 * std::pow(1.5, 5), 1e-15));
}

TEST(ParticleFactory, ClumpsInACylinderUpToAMassAvoidingWalls) {
  testing::MaterialSpec m;
  SimulationOptions opt;
  opt.dt_s = 1e-6;
  opt.seed = 11;
  Simulation sim(testing::make_table(m), opt);
  // A mesh plate across the middle of the region: nothing may be placed through it.
  const double z0 = 0.02;
  sim.add_wall([&] {
    Wall w;
    w.shape = std::make_shared<TriangleMeshShape>(
        std::vector<Triangle>{{Vec3(-0.05, -0.05, z0), Vec3(0.05, -0.05, z0), Vec3(0.05, 0.05, z0)},
                              {Vec3(-0.05, -0.05, z0), Vec3(0.05, 0.05, z0), Vec3(-0.05, 0.05, z0)}},
        "plate");
    w.material = 1;
    return w;
  }());
  FactorySpec fs;
  fs.body.spheres = {{Vec3(0.0015, 0, 0), 0.002}, {Vec3(-0.0015, 0, 0), 0.002}};  // a dumbbell
  fs.body.mass_kg = 1e-4;
  fs.body.principal_inertia_kg_m2 = Vec3(2e-10, 4e-10, 4e-10);
  fs.region.kind = InsertionRegion::Kind::cylinder;
  fs.region.base_m = Vec3(0, 0, 0);
  fs.region.radius_m = 0.02;
  fs.region.height_m = 0.04;
  fs.scale = {1.0, 0.05, 0.9, 1.1};
  fs.total_mass_kg = 0.01;
  const FactoryResult r = insert_particles(sim, fs);
  ASSERT_TRUE(r.complete) << r.stop_reason;
  EXPECT_GE(r.mass_kg, 0.01);
  EXPECT_LT(r.mass_kg, 0.01 + 1e-4 * 1.1 * 1.1 * 1.1);  // stops at the first body past the mass
  expect_no_overlap(sim);
  for (std::size_t i = 0; i < sim.spheres().size(); ++i) {
    const Vec3& p = sim.spheres().position_m[i];
    const double rr = sim.spheres().radius_m[i];
    EXPECT_GE(std::abs(p.z() - z0), rr);  // clear of the plate
    EXPECT_LE(std::hypot(p.x(), p.y()) + rr, 0.02 * (1 + 1e-12));
  }
}

TEST(ParticleFactory, ReportsWhyItStoppedShort) {
  testing::MaterialSpec m;
  SimulationOptions opt;
  opt.dt_s = 1e-6;
  Simulation sim(testing::make_table(m), opt);
  FactorySpec fs;
  fs.body = sphere_body(0.002, m.density_kg_m3, 0);
  fs.region.lo_m = Vec3::Zero();
  fs.region.hi_m = Vec3(0.01, 0.01, 0.01);  // room for a handful of 4 mm spheres only
  fs.count = 100;
  fs.max_attempts = 20000;
  const FactoryResult r = insert_particles(sim, fs);
  EXPECT_FALSE(r.complete);
  EXPECT_GT(r.placed, 0u);
  EXPECT_LT(r.placed, 100u);
  EXPECT_NE(r.stop_reason.find("placed " + std::to_string(r.placed)), std::string::npos) << r.stop_reason;
  EXPECT_NE(r.stop_reason.find("too full"), std::string::npos) << r.stop_reason;
  expect_no_overlap(sim);
}

}  // namespace
}  // namespace seedcal
