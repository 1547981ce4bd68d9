// Free rotation of an asymmetric rigid body (no forces): spun near its intermediate principal axis
// it flips periodically (the Dzhanibekov / tennis-racket instability, Euler's equations), while
// its kinetic energy and angular momentum are invariants that the integrator must keep.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "solver/integrate/free_rotation.hpp"
#include "tests/support/worlds.hpp"

namespace seedcal {
namespace {

TEST(FreeRotation, IntermediateAxisFlipsAndInvariantsHold) {
  testing::MaterialSpec m;
  SimulationOptions opt;
  opt.gravity_m_s2 = Vec3::Zero();
  opt.dt_s = 1e-4;
  Simulation sim(testing::make_table(m), opt);
  BodyDef b;
  b.spheres.push_back({Vec3::Zero(), 0.01});
  b.mass_kg = 1.0;
  b.principal_inertia_kg_m2 = Vec3(1.0, 2.0, 3.0);
  // Mostly about the intermediate axis (body y), with a small perturbation.
  b.angular_velocity_rad_s = Vec3(0.01, 10.0, 0.0);
  sim.add_body(b);
  const Vec3 L0 = sim.bodies().angular_momentum[0];
  const double e0 = sim.kinetic_energy_j();
  double worst_e = 0.0, worst_l = 0.0;
  int flips = 0;
  double prev_sign = 1.0;
  for (int s = 0; s < 100000; ++s) {
    ASSERT_TRUE(sim.step());
    const Quat& q = sim.bodies().orientation[0];
    // Body y axis in the world: it points along +L initially and along -L after a flip.
    const double along = (q * Vec3::UnitY()).dot(L0.normalized());
    if (along * prev_sign < -0.5) { ++flips; prev_sign = -prev_sign; }
    worst_e = std::max(worst_e, std::abs(sim.kinetic_energy_j() - e0) / e0);
    worst_l = std::max(worst_l, (sim.bodies().angular_momentum[0] - L0).norm() / L0.norm());
  }
  std::printf("1e5 steps: %d flips, max |dE|/E %.3e, max |dL|/|L| %.3e\n", flips, worst_e, worst_l);
  EXPECT_GE(flips, 2);
  // 1e-6: the requirement (the splitting's energy error is O((w dt)^2) = O(1e-6) and
  // bounded, with no drift; L is conserved to round-off since every sub-step is a rotation).
  EXPECT_LT(worst_e, 1e-6);
  EXPECT_LT(worst_l, 1e-6);
}

TEST(FreeRotation, SymmetricTopPrecessesAtTheEulerRate) {
  // Symmetric top I1 = I2 = 1, I3 = 2: the body-frame angular velocity precesses about the
  // symmetry axis at Omega = (I3 - I1) / I1 * w3 (Landau & Lifshitz, Mechanics, sec. 36).
  testing::MaterialSpec m;
  SimulationOptions opt;
  opt.gravity_m_s2 = Vec3::Zero();
  opt.dt_s = 1e-5;
  Simulation sim(testing::make_table(m), opt);
  BodyDef b;
  b.spheres.push_back({Vec3::Zero(), 0.01});
  b.mass_kg = 1.0;
  b.principal_inertia_kg_m2 = Vec3(1.0, 1.0, 2.0);
  b.angular_velocity_rad_s = Vec3(1.0, 0.0, 5.0);
  sim.add_body(b);
  const double omega = (2.0 - 1.0) / 1.0 * 5.0;
  const double t_end = 2.0 * M_PI / omega;  // one precession period
  ASSERT_TRUE(sim.run(static_cast<std::uint64_t>(std::llround(t_end / opt.dt_s))));
  const Quat& q = sim.bodies().orientation[0];
  const Vec3 wb = q.conjugate() * sim.bodies().angular_velocity[0];
  std::printf("body-frame w after one precession period: (%.6f, %.6f, %.6f)\n", wb.x(), wb.y(), wb.z());
  // After one period the body-frame w returns to (1, 0, 5); 1e-3 allows the step quantisation of
  // t_end (half a step of phase, 2.5e-5 rad) and the O((w dt)^2) splitting error.
  EXPECT_NEAR(wb.x(), 1.0, 1e-3);
  EXPECT_NEAR(wb.y(), 0.0, 1e-3);
  EXPECT_NEAR(wb.z(), 5.0, 1e-6);
}

// The renormalisation after each rotation step (integrate/free_rotation.hpp): a Newton step for
// 1/sqrt near unit norm, exact beyond |q|^2 - 1 = 1e-5. Its error is 3/8 e^2 in |q|, and a body
// spinning fast keeps |q| near 1 over many steps instead of drifting.
TEST(FreeRotation, RenormalisationKeepsUnitNorm) {
  for (const double e : {1e-9, 1e-7, 9.9e-6, -9.9e-6, 1e-5, 1e-3, -0.5, 3.0}) {
    Quat q(0.3, -0.4, 0.5, std::sqrt(0.5));  // unit
    q.coeffs() *= std::sqrt(1.0 + e);         // |q|^2 = 1 + e
    normalize_near_unit(q);
    const double bound = std::abs(e) < 1e-5 ? 0.375 * e * e * 1.001 + 4e-16 : 4e-16;
    EXPECT_NEAR(q.norm(), 1.0, bound) << "e = " << e;
  }
  // 1e6 steps of a body spinning at |w| h = 4e-3 rad per step (|q|^2 grows by 4e-6 each step).
  Quat q = Quat::Identity();
  const Vec3 L(0.3, -1.2, 2.0);
  const Vec3 inv_inertia(1.0, 1.0, 1.0);
  const double h = 4e-3 / L.norm();
  double worst = 0.0;
  for (int k = 0; k < 1000000; ++k) {
    free_rotation_step(q, L, inv_inertia, true, h);
    worst = std::max(worst, std::abs(q.norm() - 1.0));
  }
  std::printf("worst | |q| - 1 | over 1e6 steps at |w| h = 4e-3: %.3g\n", worst);
  EXPECT_LT(worst, 1e-11);
}

}  // namespace
}  // namespace seedcal
