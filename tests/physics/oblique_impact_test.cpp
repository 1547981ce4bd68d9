// Oblique impact of a sphere on a plane (Maw, Barber & Fawcett 1976, Wear 38, 101; Thornton &
// Yin 1991; rigid-body impulse theory, e.g. Brach 1991, "Mechanical Impact Dynamics").
//
// Gross sliding (large incidence angle): the tangential impulse is mu times the normal impulse,
//   J_n = m (1 + e) v_n,  J_t = mu J_n,
//   v_t' = v_t - mu (1 + e) v_n,   w' = w + r J_t / I = (5 / 2) mu (1 + e) v_n / r  (I = 2/5 m r^2).
// Sticking (small angle): the Mindlin tangential spring stores energy during the impact and gives
// it back, so the tangential velocity of the contact point reverses.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "solver/sim/time_step.hpp"
#include "tests/support/worlds.hpp"

namespace seedcal {
namespace {

struct Rebound {
  Vec3 v, w;
};

Rebound oblique(double vn, double vt, double e, double mu, bool clip = false) {
  testing::MaterialSpec m;
  m.restitution = e;
  m.static_friction = mu;
  const double r = 0.01;
  InteractionTable table = testing::make_table(m);
  BodyDef a = sphere_body(r, m.density_kg_m3, 0);
  const HertzImpact th = hertz_impact(a.mass_kg, r, table.pair(0, 1).e_star_pa, vn);
  SimulationOptions opt;
  opt.contact.clip_attractive = clip;
  opt.gravity_m_s2 = Vec3::Zero();
  opt.dt_s = th.contact_time_s / 4000.0;  // time discretisation error < 0.1 %
  Simulation sim(table, opt);
  a.position_m = Vec3(0, 0, r + 1e-7);
  a.velocity_m_s = Vec3(vt, 0, -vn);
  sim.add_body(a);
  sim.add_wall(testing::plane_wall(Vec3::Zero(), Vec3::UnitZ()));
  bool touched = false;
  for (int s = 0; s < 20000; ++s) {
    EXPECT_TRUE(sim.step());
    const bool touching = sim.stats().wall_contacts > 0;
    touched |= touching;
    if (touched && !touching) break;
  }
  return {sim.bodies().velocity_m_s[0], sim.bodies().angular_velocity[0]};
}

TEST(ObliqueImpact, GrossSlidingMatchesImpulseTheory) {
  // e = 0.9 with the default (unclipped) normal force, and e = 0.45 with the normal force clipped
  // at zero. Impulse theory assumes friction mu Fn with Fn >= 0 throughout; the unclipped damped
  // contact ends with a short attractive tail during which the Coulomb cap mu |Fn| (DESIGN.md)
  // still acts, which for e = 0.45 adds about 8 % to the tangential impulse (printed below; see
  // docs/contact_models.md). With e = 0.9 the tail is negligible.
  struct Case { double e; bool clip; };
  for (const Case c : {Case{0.9, false}, Case{0.45, true}, Case{0.45, false}}) {
    const double vn = 1.0, vt = 3.0, mu = 0.3, r = 0.01;
    const Rebound out = oblique(vn, vt, c.e, mu, c.clip);
    const double e_out = out.v.z() / vn;  // the normal impulse is m (1 + e_out) vn
    const double vt_theory = vt - mu * (1.0 + e_out) * vn;
    // Sliding along +x on a floor: friction acts along -x at the contact point (0, 0, -r), so the
    // spin is about +y: w_y = (5/2) mu (1+e) vn / r.
    const double w_theory = 2.5 * mu * (1.0 + e_out) * vn / r;
    std::printf("e %.2f clip %d: v_t' %.5f (theory %.5f), w_y' %.4f (theory %.4f), v_n' %.5f\n",
                c.e, c.clip, out.v.x(), vt_theory, out.w.y(), w_theory, out.v.z());
    if (!c.clip && c.e < 0.5) continue;  // reported, not asserted (see above)
    // 2 %: the requirement.
    EXPECT_NEAR(out.v.x() / vt_theory, 1.0, 0.02) << "e = " << c.e;
    EXPECT_NEAR(out.w.y() / w_theory, 1.0, 0.02) << "e = " << c.e;
  }
}

TEST(ObliqueImpact, StickingContactReversesContactPointVelocity) {
  // Below the gross-sliding limit vt < (1 + 1/K) mu (1 + e) vn (K = I / (m r^2) = 2/5) the contact
  // point stops slipping during the impact and the tangential spring stores energy. The contact
  // point obeys u'' = -(1 + 1/K) S_t u / m while the normal overlap obeys d'' = -(2/3) S_n d / m;
  // with S_t / S_n = 4 G* / E* = 2 (1 - nu) / (2 - nu) the tangential motion runs
  // Omega = sqrt(1.5 kappa (1 + 1/K)) = 2.2 times faster than the normal one (nu = 0.2), so for
  // very small incidence angles it completes about one full oscillation and the contact point
  // leaves with its incident sign (no reversal: the Hertz-Mindlin no-slip model has no micro-slip,
  // unlike Maw et al.'s theory). With initial sliding (here vt / (mu vn) = 2.4) the spring is
  // loaded late and the contact point leaves reversed. (The no-slip model's regimes are compared
  // with Maw et al.'s in Di Renzo & Di Maio 2004, Chem. Eng. Sci. 59, 525.)
  const double vn = 1.0, vt = 1.2, mu = 0.5, e = 0.9, r = 0.01;
  const Rebound out = oblique(vn, vt, e, mu);
  const double u_out = out.v.x() - out.w.y() * r;  // contact point: v + w x (0, 0, -r), x part
  const double jt_over_m = vt - out.v.x();          // tangential impulse / m
  const double jn_over_m = (1.0 + out.v.z() / vn) * vn;
  std::printf("contact point tangential velocity: in %.5f, out %.5f; Jt/(mu Jn) = %.4f\n", vt, u_out,
              jt_over_m / (mu * jn_over_m));
  EXPECT_LT(jt_over_m, 0.98 * mu * jn_over_m);  // it stuck: less than the full sliding impulse
  EXPECT_LT(u_out, -0.05 * vt);                 // and the contact point velocity reversed
}

}  // namespace
}  // namespace seedcal
