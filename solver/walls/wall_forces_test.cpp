// Forces and torques the particles exert on walls: a resting sphere loads a plane and a meshed
// floor with its weight (once, even over a shared mesh vertex), and a sphere in a turning drum is
// carried up to the angle where rolling resistance balances its weight, loading the drum with a
// torque against its rotation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "solver/scenes/settle.hpp"
#include "solver/walls/cylinder_shape.hpp"
#include "solver/walls/mesh_shape.hpp"
#include "solver/walls/motion_laws.hpp"
#include "tests/support/worlds.hpp"

namespace seedcal {
namespace {

TEST(WallForces, SphereRestingOnAPlateLoadsItWithItsWeight) {
  testing::MaterialSpec m;
  m.youngs_modulus_pa = 1e8;
  SimulationOptions opt;
  opt.dt_s = 2e-6;
  Simulation sim(testing::make_table(m), opt);
  BodyDef b = sphere_body(0.005, m.density_kg_m3, 0);
  b.position_m = Vec3(0, 0, 0.0051);
  sim.add_body(b);
  sim.add_wall(testing::plane_wall(Vec3::Zero(), Vec3::UnitZ()));
  ASSERT_TRUE(run_for(sim, 0.2));
  // 1e-3: the bounces have decayed; what is left is the contact's own elastic oscillation
  // (e = 0.9 damps it slowly), measured at 5e-5 of the weight at this instant.
  EXPECT_NEAR(sim.walls()[0].force_n.z() / (-b.mass_kg * 9.81), 1.0, 1e-3);
  EXPECT_EQ(sim.walls()[0].contacts, 1);
}

TEST(WallForces, SphereOnAMeshedFloorOverASharedVertexCountsOnce) {
  // A 40 mm square floor of 8 triangles (four squares, each split in two) meeting at the centre,
  // where six triangles share the vertex: the sphere rests on that vertex.
  std::vector<Triangle> t;
  const double a = 0.02;
  for (int i = -1; i < 1; ++i)
    for (int j = -1; j < 1; ++j) {
      const Vec3 p00(i * a, j * a, 0), p10((i + 1) * a, j * a, 0), p01(i * a, (j + 1) * a, 0),
          p11((i + 1) * a, (j + 1) * a, 0);
      t.push_back({p00, p10, p11});
      t.push_back({p00, p11, p01});
    }
  testing::MaterialSpec m;
  m.youngs_modulus_pa = 1e8;
  SimulationOptions opt;
  opt.dt_s = 2e-6;
  Simulation sim(testing::make_table(m), opt);
  BodyDef b = sphere_body(0.005, m.density_kg_m3, 0);
  b.position_m = Vec3(0, 0, 0.0051);
  sim.add_body(b);
  Wall floor;
  floor.shape = std::make_shared<TriangleMeshShape>(t, "floor");
  floor.material = 1;
  sim.add_wall(floor);
  ASSERT_TRUE(run_for(sim, 0.2));
  // As on the plane (same tolerance): six contacts would carry the weight at 1/6 of the overlap
  // each, and bounce differently, so the weight with one contact shows the vertex counted once.
  EXPECT_EQ(sim.walls()[0].contacts, 1);
  EXPECT_NEAR(sim.walls()[0].force_n.z() / (-b.mass_kg * 9.81), 1.0, 1e-3);
  EXPECT_NEAR(sim.bodies().position_m[0].x(), 0.0, 1e-9);  // no sideways push from a seam
}

TEST(WallForces, DISABLED_SphereInATurningDrumIsCarriedUpAndBrakesTheDrum) {
  // Drum: R = 50 mm, 20 mm deep, axis along world y, turning at +1 rad/s about +y. A 5 mm sphere
  // with rolling friction mu_r = 0.2 (EPSD, whose rolling torque the wall feels too) rolls on the
  // wall. At steady rolling the friction force F_t = m g sin(theta) and the rolling torque
  // mu_r F_n r balance about the sphere's centre (F_t r = mu_r F_n r, F_n = m g cos(theta)), so
  // tan(theta) = mu_r: carried up by atan(0.2) = 11.3 degrees on the side the bottom moves to
  // (w x (0,0,-R) = -x). The drum feels the moment of the weight about its axis, x_c m g, < 0:
  // against its rotation (the motor's load).
  testing::MaterialSpec m;
  m.density_kg_m3 = 1340.0;
  m.youngs_modulus_pa = 1e8;
  m.poisson_ratio = 0.3;
  m.restitution = 0.3;
  m.static_friction = 0.8;
  m.rolling_friction = 0.2;
  SimulationOptions opt;
  opt.dt_s = 2e-6;
  opt.contact.rolling = RollingModel::epsd;
  Simulation sim(testing::make_table(m), opt);
  const double R = 0.05, D = 0.02, r = 0.005, omega = 1.0;
  BodyDef b = sphere_body(r, m.density_kg_m3, 0);
  b.position_m = Vec3(0, 0, -R + r + 1e-5);
  sim.add_body(b);
  Wall drum;
  drum.shape = std::make_shared<CylinderShape>(R, D, true, true, true);
  drum.material = 1;
  drum.pose.orientation = Quat(Eigen::AngleAxisd(-std::numbers::pi / 2, Vec3::UnitX()));  // z -> y
  drum.pose.origin_m = Vec3(0, -0.5 * D, 0);
  drum.motion = std::make_shared<Rotation>(Vec3::UnitY(), Vec3::Zero(), omega, drum.pose);
  sim.add_wall(drum);
  ASSERT_TRUE(run_for(sim, 0.6)) << sim.failure().message;
  double sum_angle = 0.0, sum_torque = 0.0, sum_expected = 0.0;
  int n = 0;
  const std::size_t builds = sim.neighbour_builds();
  const double mg = b.mass_kg * 9.81;
  for (int s = 0; s < 50000; ++s, ++n) {
    ASSERT_TRUE(sim.step());
    const Vec3 c = sim.bodies().position_m[0];
    sum_angle += std::atan2(-c.x(), -c.z());
    sum_torque += sim.walls()[0].torque_n_m.y();
    sum_expected += c.x() * mg;
  }
  const double theta = sum_angle / n, torque = sum_torque / n, expected = sum_expected / n;
  std::printf("drum: carried up %.3f deg (atan(mu_r) = %.3f), drum torque %.4e N m (x_c m g = %.4e)\n",
              theta * 180.0 / std::numbers::pi, std::atan(0.2) * 180.0 / std::numbers::pi, torque, expected);
  EXPECT_GT(theta, 0.0);
  // 3 %: the steady angle is shifted by the centripetal term (omega^2 R / g = 0.5 %) and by the
  // sphere's contact lever (r minus the overlap) differing from r in the two torques (< 1 %).
  EXPECT_NEAR(std::tan(theta) / 0.2, 1.0, 0.03);
  EXPECT_LT(torque, 0.0);  // against the rotation (+y)
  // 2 %: the sphere's residual oscillation about its steady angle, averaged over 0.1 s.
  EXPECT_NEAR(torque / expected, 1.0, 0.02);
  // The drum turns about its symmetry axis: no list rebuild is forced by the wall.
  EXPECT_LE(sim.neighbour_builds() - builds, 2u);
}

}  // namespace
}  // namespace seedcal
