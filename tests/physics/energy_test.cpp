// Energy conservation of an elastic, frictionless bed in a box (restitution 1, no friction, no
// rolling resistance): kinetic + gravitational + Hertz elastic energy must stay constant up to
// the integrator's O(dt^2) error.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "tests/support/random_bed.hpp"

namespace seedcal {
namespace {

// Elastic energy of a Hertz contact: U = 8/15 E* sqrt(R*) d^(5/2) (integral of Fn).
double total_energy(const Simulation& sim) {
  const auto& B = sim.bodies();
  const auto& S = sim.spheres();
  double e = sim.kinetic_energy_j();
  for (std::size_t b = 0; b < B.size(); ++b) e -= B.mass_kg[b] * sim.options().gravity_m_s2.dot(B.position_m[b]);
  const PairConstants& pp = sim.table().pair(0, 0);
  const PairConstants& pw = sim.table().pair(0, 1);
  for (std::size_t i = 0; i < S.size(); ++i) {
    for (std::size_t j = i + 1; j < S.size(); ++j) {
      const double d = S.radius_m[i] + S.radius_m[j] - (S.position_m[i] - S.position_m[j]).norm();
      if (d > 0) {
        const double rs = S.radius_m[i] * S.radius_m[j] / (S.radius_m[i] + S.radius_m[j]);
        e += 8.0 / 15.0 * pp.e_star_pa * std::sqrt(rs) * std::pow(d, 2.5);
      }
    }
    for (const Wall& w : sim.walls()) {
      WallHit hit;
      if (w.shape->nearest(0, to_wall_frame(w.pose, S.position_m[i]), S.radius_m[i], hit)) {
        const double d = S.radius_m[i] - hit.distance;
        if (d > 0) e += 8.0 / 15.0 * pw.e_star_pa * std::sqrt(S.radius_m[i]) * std::pow(d, 2.5);
      }
    }
  }
  return e;
}

TEST(Energy, ElasticFrictionlessBedConservesEnergy) {
  testing::MaterialSpec m;
  m.density_kg_m3 = 1340.0;
  m.youngs_modulus_pa = 1.65e8;
  m.poisson_ratio = 0.4;
  m.restitution = 1.0;
  m.static_friction = 0.0;
  InteractionTable table = testing::make_table(m);
  SimulationOptions opt;
  opt.dt_s = 1e-6;
  Simulation probe(table, opt);
  probe.add_body(sphere_body(0.002, m.density_kg_m3, 0));
  opt.dt_s = 0.2 * probe.rayleigh_time_step_s();
  opt.seed = 7;
  Simulation sim(table, opt);
  testing::BedSpec bed;
  bed.nx = bed.ny = 6;
  bed.nz = 6;
  testing::add_random_bed(sim, bed, m.density_kg_m3);
  const double e0 = total_energy(sim);
  double worst = 0.0;
  std::size_t contacts = 0;
  std::size_t contact_steps = 0;
  for (int block = 0; block < 40; ++block) {
    for (int s = 0; s < 1000; ++s) {
      ASSERT_TRUE(sim.step()) << sim.failure().message;
      const std::size_t c = sim.stats().sphere_contacts + sim.stats().wall_contacts;
      contacts = std::max(contacts, c);
      contact_steps += c;
    }
    worst = std::max(worst, std::abs(total_energy(sim) - e0) / e0);
  }
  std::printf("216 spheres, 40000 steps at 0.2 Rayleigh: max relative energy error %.3e (up to %zu "
              "contacts at once, %zu contact-steps)\n", worst, contacts, contact_steps);
  // The bed collides for real: a crowd of simultaneous contacts and many resolved collisions
  // (one collision lasts ~20 steps at this time step).
  EXPECT_GT(contacts, 40u);
  EXPECT_GT(contact_steps, 100000u);
  // 1e-3: velocity Verlet's bounded O(dt^2) error at 0.2 of the Rayleigh step; a missed contact
  // or wrong force would show as a drift of order 1e-2 or more.
  EXPECT_LT(worst, 1e-3);
}

}  // namespace
}  // namespace seedcal
