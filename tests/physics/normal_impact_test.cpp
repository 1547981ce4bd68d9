// Normal impacts against Hertz theory (Johnson 1985, "Contact Mechanics", sec. 11.4) and the set
// restitution (Hertz-Mindlin damping of Tsuji et al. 1992 as in DESIGN.md).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "solver/sim/time_step.hpp"
#include "tests/support/worlds.hpp"

namespace seedcal {
namespace {

using testing::MaterialSpec;

struct Outcome {
  double contact_time_s = 0.0, max_overlap_m = 0.0, max_force_n = 0.0, rebound_speed = 0.0;
};

// Two equal spheres meeting head-on at relative speed v (wall = false), or one sphere hitting a
// plane at speed v (wall = true). No gravity. dt = contact time / 4000, so the time discretisation
// error of the measured contact time is below 1/4000 (0.025 %).
Outcome impact(const MaterialSpec& m, double v, bool wall, bool clip = false,
               double wall_modulus = -1.0) {
  const double r = 0.01;
  InteractionTable table = testing::make_table(m, wall_modulus);
  BodyDef a = sphere_body(r, m.density_kg_m3, 0);
  const double mass = a.mass_kg;
  const double estar = wall ? table.pair(0, 1).e_star_pa : table.pair(0, 0).e_star_pa;
  const double mstar = wall ? mass : 0.5 * mass;
  const double rstar = wall ? r : 0.5 * r;
  const HertzImpact th = hertz_impact(mstar, rstar, estar, v);
  SimulationOptions opt;
  opt.gravity_m_s2 = Vec3::Zero();
  opt.dt_s = th.contact_time_s / 4000.0;
  opt.contact.clip_attractive = clip;
  Simulation sim(table, opt);
  const double gap = 1e-6;
  if (wall) {
    a.position_m = Vec3(0, 0, r + gap);
    a.velocity_m_s = Vec3(0, 0, -v);
    sim.add_body(a);
    sim.add_wall(testing::plane_wall(Vec3::Zero(), Vec3::UnitZ()));
  } else {
    BodyDef b = a;
    a.position_m = Vec3(-r - gap, 0, 0);
    a.velocity_m_s = Vec3(0.5 * v, 0, 0);
    b.position_m = Vec3(r + gap, 0, 0);
    b.velocity_m_s = Vec3(-0.5 * v, 0, 0);
    sim.add_body(a);
    sim.add_body(b);
  }
  Outcome o;
  double t_on = -1.0;
  const auto max_steps = static_cast<std::uint64_t>(3.0 * th.contact_time_s / opt.dt_s) + 1000;
  for (std::uint64_t s = 0; s < max_steps; ++s) {
    EXPECT_TRUE(sim.step()) << sim.failure().message;
    const bool touching = sim.stats().sphere_contacts + sim.stats().wall_contacts > 0;
    if (touching && t_on < 0) t_on = sim.time_s();
    if (!touching && t_on >= 0) {
      o.contact_time_s = sim.time_s() - t_on;
      break;
    }
    o.max_overlap_m = std::max(o.max_overlap_m, sim.stats().max_overlap_m);
    o.max_force_n = std::max(o.max_force_n, sim.stats().max_normal_force_n);
  }
  const auto& V = sim.bodies().velocity_m_s;
  o.rebound_speed = wall ? V[0].z() : V[1].x() - V[0].x();
  // Theory for comparison (elastic): stored in the outcome's caller.
  return o;
}

void expect_hertz(bool wall) {
  MaterialSpec m;
  m.restitution = 1.0;  // Hertz theory is elastic
  const double v = 2.0;
  const Outcome o = impact(m, v, wall);
  const double r = 0.01;
  InteractionTable table = testing::make_table(m);
  const double mass = sphere_body(r, m.density_kg_m3, 0).mass_kg;
  const HertzImpact th = hertz_impact(wall ? mass : 0.5 * mass, wall ? r : 0.5 * r,
                                      wall ? table.pair(0, 1).e_star_pa : table.pair(0, 0).e_star_pa, v);
  std::printf("%s: contact time %.6e s (theory %.6e), max overlap %.6e m (%.6e), max force %.6e N (%.6e)\n",
              wall ? "sphere-wall" : "sphere-sphere", o.contact_time_s, th.contact_time_s,
              o.max_overlap_m, th.max_overlap_m, o.max_force_n, th.max_force_n);
  // 1 %: the requirement; the discretisation error at dt = t_c/4000 is far smaller.
  EXPECT_NEAR(o.contact_time_s / th.contact_time_s, 1.0, 0.01);
  EXPECT_NEAR(o.max_overlap_m / th.max_overlap_m, 1.0, 0.01);
  EXPECT_NEAR(o.max_force_n / th.max_force_n, 1.0, 0.01);
}

TEST(NormalImpact, SphereSphereMatchesHertz) { expect_hertz(false); }
TEST(NormalImpact, SphereWallMatchesHertz) { expect_hertz(true); }

TEST(NormalImpact, RestitutionOutEqualsRestitutionIn) {
  for (bool wall : {false, true})
    for (double e : {0.1, 0.45, 0.9}) {
      MaterialSpec m;
      m.restitution = e;
      const double v = 2.0;
      const Outcome o = impact(m, v, wall);
      const double e_out = o.rebound_speed / v;
      std::printf("%s e_in %.2f e_out %.5f\n", wall ? "wall" : "pair", e, e_out);
      // 1 %: the requirement.
      EXPECT_NEAR(e_out / e, 1.0, 0.01) << (wall ? "sphere-wall" : "sphere-sphere") << " e = " << e;
    }
}

TEST(NormalImpact, ClippingAttractionRaisesRestitution) {
  // Clipping the normal force at zero removes the attractive end of the damped contact, so less
  // momentum is taken back and the rebound is faster. For e = 0.45 the literature value is about
  // 0.51 (e.g. Schwager & Poeschel 2007, Phys. Rev. E 75, 051304; Thornton et al. 2013).
  MaterialSpec m;
  m.restitution = 0.45;
  const double v = 2.0;
  const double e_clip = impact(m, v, true, true).rebound_speed / v;
  const double e_free = impact(m, v, true, false).rebound_speed / v;
  std::printf("e_in 0.45: unclipped %.4f, clipped %.4f\n", e_free, e_clip);
  EXPECT_GT(e_clip, e_free + 0.03);
  EXPECT_NEAR(e_clip, 0.51, 0.02);  // "about 0.51": within 0.02 of the quoted value
}

TEST(NormalImpact, RigidWallUsesParticleModulusOnly) {
  // A wall with E = 1e14 Pa stands for a rigid wall: E* -> E / (1 - nu^2) of the particle.
  MaterialSpec m;
  m.restitution = 1.0;
  const Outcome o = impact(m, 2.0, true, false, 1e14);
  const double r = 0.01;
  const double mass = sphere_body(r, m.density_kg_m3, 0).mass_kg;
  const double estar = testing::e_star(m.youngs_modulus_pa, m.poisson_ratio, 1e14, m.poisson_ratio);
  const HertzImpact th = hertz_impact(mass, r, estar, 2.0);
  EXPECT_NEAR(o.contact_time_s / th.contact_time_s, 1.0, 0.01);
}

}  // namespace
}  // namespace seedcal
