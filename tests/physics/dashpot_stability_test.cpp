// Stability of the contact dashpots in many-contact packings (contact/contact_law.hpp, "Which
// velocity each term uses"; docs/stability.md, "Dashpot velocity").
//
// A body whose contacts damp it at the rate g is stable under the half-step dashpot velocity for
// g dt < 2 and under the predicted end-of-step velocity only for g dt < 1. The first test measures
// both limits on the one mode where g is known in closed form: the spin of a sphere held by four
// stuck wall contacts. The second runs the rig where the predicted velocity failed: the 200 kPa
// direct shear of one-sphere seeds, which the energy guard stopped during consolidation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <tuple>

#include "solver/contact/normal_damping.hpp"
#include "solver/scenes/direct_shear.hpp"
#include "tests/support/worlds.hpp"

namespace seedcal {
namespace {

constexpr double kR = 0.004;
constexpr double kForceN = 20.0;  // per contact: a 9 mm seed's share of 200 kPa

struct SpinResult {
  double g_dt;       // the spin's damping rate times the step
  double w_ratio;    // |w| after the run / |w| at the start
};

// A sphere pressed by four side walls (x and y, each at kForceN), spinning about z with every
// contact stuck (friction far above what the spin can mobilise), no gravity: the spin is a single
// mode with stiffness k = 4 S_t l^2 and damping c = 4 c_t l^2 about I = 2/5 m r^2, l = r - d the
// lever from the centre to the contact point. The step is chosen to give g dt = `g_dt`.
SpinResult spin_between_walls(double g_dt, bool predicted, double restitution) {
  testing::MaterialSpec m = testing::table6_seed();
  m.restitution = restitution;
  m.static_friction = 1e3;
  InteractionTable table = testing::make_table(m, 2.0e10, 0.3);
  const PairConstants& pc = table.pair(0, 1);
  BodyDef b = sphere_body(kR, m.density_kg_m3, 0);
  // Overlap for kForceN: F = 4/3 E* sqrt(R) d^1.5 (R* = r against a wall).
  const double d = std::pow(kForceN / (4.0 / 3.0 * pc.e_star_pa * std::sqrt(kR)), 2.0 / 3.0);
  const double sn = 2.0 * pc.e_star_pa * std::sqrt(kR * d);
  const double st = sn * pc.sqrt_tangential_ratio * pc.sqrt_tangential_ratio;
  const double ct = -2.0 * lanes::kSqrtFiveSixths * pc.beta * std::sqrt(st * b.mass_kg);
  const double lever = kR - d, inertia = b.principal_inertia_kg_m2.z();
  const double g = 4.0 * ct * lever * lever / inertia;

  SimulationOptions opt;
  opt.gravity_m_s2 = Vec3::Zero();
  opt.contact.dashpot_predicted = predicted;
  opt.dt_s = g_dt / g;
  Simulation sim(table, opt);
  const double w0 = 10.0;
  b.angular_velocity_rad_s = Vec3(0.0, 0.0, w0);
  sim.add_body(b);
  for (const Vec3& n : {Vec3(1, 0, 0), Vec3(-1, 0, 0), Vec3(0, 1, 0), Vec3(0, -1, 0)})
    sim.add_wall(testing::plane_wall(-(kR - d) * n, n));
  // 400 steps: a decaying mode loses all but (1 - g dt)^400 of its spin, a growing one is past the
  // guard long before.
  sim.run(400);
  const double w = sim.failure().status == RunStatus::ok ? sim.bodies().angular_velocity[0].norm()
                                                       : std::numeric_limits<double>::infinity();
  return {g_dt, w / w0};
}

TEST(DashpotStability, SpinOfAHeldSphereMatchesBothLimits) {
  // e = 0.05: damping dominates the spring (g / omega = 4 |beta| sqrt(5/6) sqrt(2.5), about 4), so
  // the limits are the dashpot's own and the springs move them little (docs/stability.md).
  for (const auto& [g_dt, predicted, stable] :
       {std::tuple{0.6, true, true}, std::tuple{1.2, true, false}, std::tuple{1.5, true, false},
        std::tuple{0.6, false, true}, std::tuple{1.2, false, true}, std::tuple{1.6, false, true}}) {
    const SpinResult r = spin_between_walls(g_dt, predicted, 0.05);
    std::printf("%s dashpot, g dt = %.2f: |w| / |w0| = %.3g\n", predicted ? "predicted" : "half-step",
                r.g_dt, r.w_ratio);
    if (stable) EXPECT_LT(r.w_ratio, 1e-3) << "g dt " << g_dt << (predicted ? " predicted" : " half-step");
    else EXPECT_GT(r.w_ratio, 1.0) << "g dt " << g_dt << (predicted ? " predicted" : " half-step");
  }
}

// The direct shear of Jinong 1 at 200 kPa (quick rig) with one-sphere seeds, no rolling friction
// and static friction 0.9: under the predicted dashpot velocity the energy guard stopped it during
// consolidation at the default step (0.39 s in), at every seed; with the half-step velocity it
// runs to the end of shear.
TEST(DashpotStability, OneSphereSeedsAt200kPaShearToTheEnd) {
  DirectShearSpec spec;
  spec.physics.materials = {{"seed", 1340.0, 1.65e8, 0.4}, {"steel", 7850.0, 2.0e10, 0.3}};
  spec.physics.interactions = {{"seed_seed", 0, 0, 0.45, 0.9, 0.0}, {"seed_steel", 0, 1, 0.65, 0.4, 0.0}};
  spec.physics.contact.rolling = RollingModel::none;
  spec.seeds.body = sphere_body(0.00435, 1340.0, 0);
  spec.box_material = 1;
  spec.shear_speed_m_s = 0.02;
  spec.shear_displacement_m = 0.0045;
  spec.seed = 1;
  const DirectShearResult r = run_direct_shear(spec);
  EXPECT_EQ(r.run.failure.status, RunStatus::ok) << r.run.failure.message;
  EXPECT_EQ(r.run.stop_reason, "shear displacement reached");
  // A stress ratio tau / sigma inside the range of cohesionless granular assemblies, tan 6 deg to
  // tan 45 deg (a packing of frictional spheres without rolling resistance sits near tan 20-25 deg).
  EXPECT_GT(r.shear_strength_pa, 0.1 * spec.normal_stress_pa);
  EXPECT_LT(r.shear_strength_pa, spec.normal_stress_pa);
}

}  // namespace
}  // namespace seedcal
