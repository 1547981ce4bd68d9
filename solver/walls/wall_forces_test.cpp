// Forces and torques the particles exert on walls: a resting sphere loads a plane and a meshed
// floor with its weight (once, even over a shared mesh vertex), and a sphere in a turning drum is
// carried up to the angle where rolling resistance balances its weight, loading the drum with a
// torque against its rotation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "solver/sim/settle.hpp"
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

// The contact pass skips the frame rotation of a wall whose orientation is the identity: the same
// floor as a plane of normal z in an unturned frame and as a plane of normal x in a frame turned
// -90 deg about y (its normal then points up) carries a sliding, spinning sphere alike. The two
// differ only in the rotations' rounding (a few ulp of each contact quantity), so the trajectories
// agree to far below the 1e-9 relative bound over the 0.05 s of sliding and rolling.
TEST(WallForces, TurnedAndUnturnedFramesOfOnePlaneGiveTheSameContact) {
  testing::MaterialSpec m;
  m.youngs_modulus_pa = 1e8;
  SimulationOptions opt;
  opt.dt_s = 2e-6;
  opt.contact.rolling = RollingModel::cdt;
  const auto run = [&](bool turned) {
    Simulation sim(testing::make_table(m), opt);
    BodyDef b = sphere_body(0.005, m.density_kg_m3, 0);
    b.position_m = Vec3(0, 0, 0.0049);
    b.velocity_m_s = Vec3(0.3, 0.1, 0.0);
    b.angular_velocity_rad_s = Vec3(5.0, -20.0, 3.0);
    sim.add_body(b);
    Wall w = testing::plane_wall(Vec3(0.0, 0.0, 0.0), turned ? Vec3::UnitX() : Vec3::UnitZ());
    if (turned) w.pose.orientation = Quat(Eigen::AngleAxisd(-std::numbers::pi / 2, Vec3::UnitY()));
    sim.add_wall(w);
    EXPECT_TRUE(run_for(sim, 0.05));
    return std::pair{sim.bodies().position_m[0], sim.bodies().velocity_m_s[0]};
  };
  const auto [x0, v0] = run(false);
  const auto [x1, v1] = run(true);
  EXPECT_GT(x0.x(), 0.005);  // it slid
  EXPECT_NEAR((x1 - x0).norm() / x0.norm(), 0.0, 1e-9);
  EXPECT_NEAR((v1 - v0).norm() / v0.norm(), 0.0, 1e-9);
}

// A pair of materials with no interaction would pass through each other with zero force: the
// simulation refuses the body or wall that brings such a pair into the world, whichever comes last.
TEST(WallForces, MaterialPairWithoutAnInteractionIsRefused) {
  const std::vector<Material> mats = {{"glass", 2800.0, 4.8e10, 0.2}, {"steel", 7800.0, 2e11, 0.3}};
  const InteractionTable only_glass(mats, {{"gg", 0, 0, 0.9, 0.3, 0.0}});
  SimulationOptions opt;
  opt.dt_s = 1e-7;
  const BodyDef glass = sphere_body(0.005, 2800.0, 0);
  BodyDef steel = sphere_body(0.005, 7800.0, 1);
  steel.position_m = Vec3(0, 0, 0.02);
  auto steel_plane = [] {
    Wall w = testing::plane_wall(Vec3::Zero(), Vec3::UnitZ());
    w.material = 1;
    return w;
  };
  {
    Simulation sim(only_glass, opt);
    sim.add_body(glass);
    EXPECT_THROW(sim.add_wall(steel_plane()), std::invalid_argument);
  }
  {
    Simulation sim(only_glass, opt);
    sim.add_wall(steel_plane());
    try {
      sim.add_body(glass);
      ADD_FAILURE() << "a glass body over a steel wall without a glass-steel interaction was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("'glass' and 'steel' have no interaction"), std::string::npos) << e.what();
    }
  }
  {
    Simulation sim(only_glass, opt);
    sim.add_body(glass);
    EXPECT_THROW(sim.add_body(steel), std::invalid_argument);  // steel-glass and steel-steel missing
  }
  {
    Simulation sim(InteractionTable(mats, {{"gg", 0, 0, 0.9, 0.3, 0.0}, {"gs", 0, 1, 0.9, 0.3, 0.0}}), opt);
    sim.add_wall(steel_plane());
    EXPECT_NO_THROW(sim.add_body(glass));  // every pair that can touch is defined (steel-steel is not needed)
  }
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

TEST(WallForces, SphereInATurningDrumIsCarriedUpAndBrakesTheDrum) {
  // Drum: R = 50 mm, 20 mm deep, axis along world y, turning at +1 rad/s about +y. A 5 mm sphere
  // with rolling friction mu_r = 0.2 (EPSD, whose rolling torque the wall feels too) is carried up
  // on the side the bottom moves to (w x (0,0,-R) = -x), held by its rolling spring, until the
  // spring yields; then it rolls back and oscillates about the angle where rolling resistance
  // balances its weight: F_t = m g sin(theta) and the rolling torque mu_r F_n r balance about its
  // centre (F_t r = mu_r F_n r, F_n = m g cos(theta)), so tan(theta) = mu_r, 11.31 degrees. The
  // oscillation is slowly damped (period ~0.5 s, turning points 7.0 and 15.7 degrees), so the
  // test takes the midpoint of its extremes over two periods. The drum feels, on average over
  // whole periods, the moment of the weight about its axis, x_c m g < 0: against its rotation
  // (the motor's load).
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
  auto angle = [&] {
    const Vec3 c = sim.bodies().position_m[0];
    return std::atan2(-c.x(), -c.z());
  };
  // Carried up with the wall at first: after 0.2 s (0.2 rad of drum turn) it is still held.
  ASSERT_TRUE(run_for(sim, 0.2)) << sim.failure().message;
  EXPECT_GT(angle(), 0.8 * 0.2 * R / (R - r));  // the centre's arc: R / (R - r) x the drum's
  ASSERT_TRUE(run_for(sim, 0.3)) << sim.failure().message;
  double lo = 1e9, hi = -1e9, sum_torque = 0.0, sum_expected = 0.0;
  const double mg = b.mass_kg * 9.81;
  const int n = 1000000;  // 2 s, about four periods
  for (int s = 0; s < n; ++s) {
    ASSERT_TRUE(sim.step());
    lo = std::min(lo, angle());
    hi = std::max(hi, angle());
    sum_torque += sim.walls()[0].torque_n_m.y();
    sum_expected += sim.bodies().position_m[0].x() * mg;
  }
  const double theta = 0.5 * (lo + hi), torque = sum_torque / n, expected = sum_expected / n;
  const double deg = 180.0 / std::numbers::pi;
  std::printf("drum: oscillates %.3f..%.3f deg, midpoint %.3f deg (atan(mu_r) = %.3f); mean drum "
              "torque %.5e N m (mean x_c m g = %.5e, ratio %.4f)\n",
              lo * deg, hi * deg, theta * deg, std::atan(0.2) * deg, torque, expected, torque / expected);
  // 3 %: the centripetal term shifts the balance by omega^2 R / g = 0.5 %, the lever (r less the
  // overlap) differs between the two torques by < 0.1 %, and the oscillation about the balance is
  // not exactly symmetric (its midpoint drifts by ~0.05 degrees between periods).
  EXPECT_NEAR(std::tan(theta) / 0.2, 1.0, 0.03);
  EXPECT_LT(torque, 0.0);  // against the rotation (+y)
  // 1 %: over a window that is not a whole number of periods the sphere's angular momentum about
  // the axis changes by at most ~1.3e-7 kg m2/s, 0.1 % of the mean moment over 2 s.
  EXPECT_NEAR(torque / expected, 1.0, 0.01);
}

}  // namespace
}  // namespace seedcal
