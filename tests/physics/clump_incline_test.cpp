// Clumps resting on an incline (gravity tilted by theta against the plane z = 0): static friction
// and CDT rolling resistance of multi-sphere bodies against analytical limits.
//
//  - Sliding (a three-sphere "tripod" lying flat, which cannot roll): Coulomb friction holds the
//    body below the friction angle, tan(theta) < mu_s, and above it the body slides with
//    a = g (sin(theta) - mu_s cos(theta)) (any dynamics text, e.g. Meriam & Kraige, Dynamics, 3/3).
//  - Rolling (a two-sphere "dumbbell" whose spheres touch the plane side by side, rolling about the
//    axis through both centres like a wheel): each sphere contact carries the CDT torque
//    mu_r Fn R', R' = r - overlap (contact/rolling_cdt.hpp). With both contacts the total is
//    mu_r m g cos(theta) R', so the body is held while tan(theta) < mu_r R'/r and otherwise rolls
//    without slip with a = g (sin(theta) - mu_r cos(theta) R'/r) / (1 + I/(m r^2)) (torque balance
//    about the contact line, as in tests/physics/rolling_test.cpp); for two equal spheres I about
//    their common axis is 2 x 2/5 m_s r^2 = 2/5 m r^2, so a = 5/7 g (sin - mu_r cos R'/r).
//  - The same with EDEM's lever (contact.rolling_lever = "centre_of_mass"): each contact point lies
//    below its sphere's centre, a half-spacing s = 2.5 mm off the centre of mass, so the lever is
//    L = sqrt(R'^2 + s^2) = 1.6 R' and the body is held while tan(theta) < mu_r L / R', rolling
//    above at a = 5/7 g (sin - mu_r cos L / r).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "solver/clump/mass_properties.hpp"
#include "tests/support/worlds.hpp"

namespace seedcal {
namespace {

constexpr double kG = 9.81;
constexpr double kR = 0.002;  // sphere radius, m (a seed-sized clump)

// A clump of `spheres` (lowest point on z = 0) on a steel-like plane, seed-like material (the
// paper's Table 6 Jinong 1 values), gravity tilted by theta about y (downhill is +x).
Simulation incline(const std::vector<SphereXYZR>& spheres, double mu_s, double mu_r, double theta_deg,
                   bool lever_from_centre_of_mass = false) {
  testing::MaterialSpec m = testing::table6_seed();
  m.static_friction = mu_s;
  m.rolling_friction = mu_r;
  InteractionTable table = testing::make_table(m, 2e10, 0.3);
  BodyDef b = clump_body(spheres, m.density_kg_m3, 0);
  // Keep the input frame (clump_body rotates into the principal frame and back via orientation).
  double lowest = 1e9;
  for (const SphereDef& s : b.spheres) lowest = std::min(lowest, (b.orientation * s.offset_m).z() - s.radius_m);
  b.position_m = Vec3(0, 0, -lowest);
  const double th = theta_deg * std::numbers::pi / 180.0;
  SimulationOptions opt;
  opt.gravity_m_s2 = Vec3(kG * std::sin(th), 0.0, -kG * std::cos(th));
  opt.contact.rolling = RollingModel::cdt;
  opt.contact.cdt_lever_from_centre_of_mass = lever_from_centre_of_mass;
  return testing::body_on_plane(table, opt, b);
}

std::vector<SphereXYZR> tripod() {
  std::vector<SphereXYZR> s;
  for (int k = 0; k < 3; ++k) {
    const double a = 2.0 * std::numbers::pi * k / 3.0;
    s.push_back({Vec3(0.003 * std::cos(a), 0.003 * std::sin(a), 0.0), kR});
  }
  return s;
}

// Two spheres side by side along y (no overlap): the axis through their centres is y, so the
// body rolls downhill along x like a wheel.
std::vector<SphereXYZR> dumbbell() { return {{Vec3(0, -0.0025, 0), kR}, {Vec3(0, 0.0025, 0), kR}}; }

// Mean x-acceleration over [t0, t0 + span] after letting the landing transient decay for t0.
double downhill_acceleration(Simulation& sim, double t0, double span, double* moved = nullptr) {
  EXPECT_TRUE(sim.run(static_cast<std::uint64_t>(t0 / sim.options().dt_s))) << sim.failure().message;
  const double v0 = sim.bodies().velocity_m_s[0].x(), x0 = sim.bodies().position_m[0].x();
  const double ts = sim.time_s();
  EXPECT_TRUE(sim.run(static_cast<std::uint64_t>(span / sim.options().dt_s))) << sim.failure().message;
  if (moved) *moved = sim.bodies().position_m[0].x() - x0;
  return (sim.bodies().velocity_m_s[0].x() - v0) / (sim.time_s() - ts);
}

TEST(ClumpIncline, TripodHeldBelowFrictionAngle) {
  const double mu = 0.4;  // friction angle 21.8 deg
  Simulation sim = incline(tripod(), mu, 0.0, 18.0);
  double moved = 0.0;
  const double a = downhill_acceleration(sim, 0.05, 0.2, &moved);
  std::printf("tripod at 18 deg: a = %.3e m/s2, moved %.3e m in 0.2 s\n", a, moved);
  // Held: no creep beyond the elastic tangential spring (sub-micrometre here).
  EXPECT_LT(std::abs(moved), 1e-6);
  EXPECT_LT(std::abs(a), 1e-3);
}

TEST(ClumpIncline, TripodSlidesAboveFrictionAngleAtCoulombRate) {
  const double mu = 0.4, th = 26.0 * std::numbers::pi / 180.0;
  Simulation sim = incline(tripod(), mu, 0.0, 26.0);
  const double a = downhill_acceleration(sim, 0.05, 0.1);
  const double theory = kG * (std::sin(th) - mu * std::cos(th));
  std::printf("tripod at 26 deg: a = %.5f m/s2, theory %.5f\n", a, theory);
  EXPECT_NEAR(a / theory, 1.0, 0.01);
}

TEST(ClumpIncline, DumbbellHeldByRollingFrictionBelowItsAngle) {
  const double mu_r = 0.1;  // held while tan(theta) < ~0.1 (5.7 deg)
  Simulation sim = incline(dumbbell(), 0.5, mu_r, 3.0);
  double moved = 0.0;
  const double a = downhill_acceleration(sim, 0.05, 0.2, &moved);
  std::printf("dumbbell at 3 deg: a = %.3e m/s2, moved %.3e m in 0.2 s\n", a, moved);
  // Held up to the CDT spin jitter at rest (docs/contact_models.md: one step's torque impulse,
  // about 1e-3 rad/s here, i.e. a few um/s at the surface): rolling freely it would cover
  // 5/7 g sin(3 deg) t^2 / 2 = 7 mm in the same 0.2 s.
  EXPECT_LT(std::abs(moved), 1e-5);
}

TEST(ClumpIncline, DumbbellRollsAboveItsAngleAtCdtRate) {
  const double mu_r = 0.1, th = 12.0 * std::numbers::pi / 180.0;
  Simulation sim = incline(dumbbell(), 0.5, mu_r, 12.0);
  const double a = downhill_acceleration(sim, 0.05, 0.1);
  const double lever = sim.bodies().position_m[0].z();  // centre height above the plane: R' = r - overlap
  const double theory = 5.0 / 7.0 * kG * (std::sin(th) - mu_r * std::cos(th) * lever / kR);
  std::printf("dumbbell at 12 deg: a = %.5f m/s2, theory %.5f (R' %.4e m)\n", a, theory, lever);
  EXPECT_NEAR(a / theory, 1.0, 0.01);
  // Rolling without slip about y: w_y r' = v_x.
  EXPECT_NEAR(sim.bodies().angular_velocity[0].y() * lever / sim.bodies().velocity_m_s[0].x(), 1.0, 0.01);
}

// EDEM's lever: at 7 deg the sphere lever would let the dumbbell roll (tan 7 deg = 0.123 > 0.1),
// the centre-of-mass lever (1.6 times longer) holds it.
TEST(ClumpIncline, CentreOfMassLeverHoldsWhereTheSphereLeverRolls) {
  const double mu_r = 0.1;
  Simulation held = incline(dumbbell(), 0.5, mu_r, 7.0, true);
  double moved = 0.0;
  downhill_acceleration(held, 0.05, 0.2, &moved);
  EXPECT_LT(std::abs(moved), 1e-5) << "centre-of-mass lever";
  Simulation rolls = incline(dumbbell(), 0.5, mu_r, 7.0, false);
  downhill_acceleration(rolls, 0.05, 0.2, &moved);
  EXPECT_GT(moved, 1e-4) << "sphere lever";
}

TEST(ClumpIncline, CentreOfMassLeverRollsAtItsRate) {
  const double mu_r = 0.1, th = 12.0 * std::numbers::pi / 180.0;
  Simulation sim = incline(dumbbell(), 0.5, mu_r, 12.0, true);
  const double a = downhill_acceleration(sim, 0.05, 0.1);
  const double h = sim.bodies().position_m[0].z();  // R': the centre of mass is at the spheres' height
  const double lever = std::sqrt(h * h + 0.0025 * 0.0025);
  const double theory = 5.0 / 7.0 * kG * (std::sin(th) - mu_r * std::cos(th) * lever / kR);
  std::printf("dumbbell, centre-of-mass lever, 12 deg: a = %.5f m/s2, theory %.5f (L %.4e m)\n", a, theory, lever);
  EXPECT_NEAR(a / theory, 1.0, 0.02);
}

}  // namespace
}  // namespace seedcal
