// Energy conservation of an elastic, frictionless bed in a box (restitution 1, no friction, no
// rolling resistance): kinetic + gravitational + Hertz elastic energy must stay constant up to
// the integrator's O(dt^2) error, and with a moving lid change by exactly the lid's work
// (Simulation::wall_work_j()). The energy guard counts that work: a column of seeds that a servo
// lid loaded and that buckles gives back what the lid stored in it, and runs on.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "solver/walls/motion_laws.hpp"
#include "solver/walls/servo_wall.hpp"
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

// Table 6's seed made elastic and frictionless: restitution 1, no friction, no rolling resistance.
testing::MaterialSpec elastic_frictionless() {
  testing::MaterialSpec m = testing::table6_seed();
  m.restitution = 1.0;
  m.static_friction = 0.0;
  m.rolling_friction = 0.0;
  return m;
}

// Options stepping spheres of radius `radius_m` of material 0 at `fraction` of their Rayleigh step.
SimulationOptions rayleigh_options(const InteractionTable& table, double radius_m, double fraction) {
  SimulationOptions opt;
  opt.dt_s = 1e-6;  // any; only the Rayleigh step is read
  Simulation probe(table, opt);
  probe.add_body(sphere_body(radius_m, table.materials()[0].density_kg_m3, 0));
  opt.dt_s = fraction * probe.rayleigh_time_step_s();
  return opt;
}

// A bed of 6 x 6 x 6 elastic, frictionless spheres of 2 mm in a box, flying at random (seed 7).
Simulation elastic_bed(const testing::BedSpec& bed) {
  const testing::MaterialSpec m = elastic_frictionless();
  const InteractionTable table = testing::make_table(m);
  SimulationOptions opt = rayleigh_options(table, bed.radius_m, 0.2);
  opt.seed = 7;
  Simulation sim(table, opt);
  testing::add_random_bed(sim, bed, m.density_kg_m3);
  return sim;
}

testing::BedSpec six_cubed() {
  testing::BedSpec bed;
  bed.nx = bed.ny = bed.nz = 6;
  return bed;
}

TEST(Energy, ElasticFrictionlessBedConservesEnergy) {
  Simulation sim = elastic_bed(six_cubed());
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

// The same bed with a lid (a plane facing down) that comes down at 0.05 m/s from above the bed and
// compresses it: the bed's total energy changes by the lid's work, -sum F . v dt.
TEST(Energy, MovingLidChangesTheEnergyByItsWork) {
  const testing::BedSpec bed = six_cubed();
  Simulation sim = elastic_bed(bed);
  const double top = bed.nz * bed.spacing * bed.radius_m;
  Wall lid = testing::plane_wall(Vec3(0, 0, top + 0.001), -Vec3::UnitZ());
  lid.motion = std::make_shared<ConstantVelocity>(Vec3(0, 0, -0.05));
  const std::size_t lid_index = sim.add_wall(lid);
  ASSERT_TRUE(sim.run(1)) << sim.failure().message;
  // The work of the first step is in both E0 and W: start both after it.
  const double e0 = total_energy(sim), w0 = sim.wall_work_j();
  double worst = 0.0, work = 0.0;
  for (int block = 0; block < 20; ++block) {
    ASSERT_TRUE(sim.run(1000)) << sim.failure().message;
    work = sim.wall_work_j() - w0;
    worst = std::max(worst, std::abs(total_energy(sim) - e0 - work) / std::max(e0, work));
  }
  const double travel = top + 0.001 - sim.walls()[lid_index].pose.origin_m.z();
  std::printf("lid down %.2f mm: work %.4e J on a bed of %.4e J; max |E - E0 - W| / max(E0, W) %.3e\n",
              1e3 * travel, work, e0, worst);
  // The lid pressed into the bed for real: its work is a good part of the bed's energy.
  EXPECT_GT(work, 0.2 * e0);
  // 2e-3: Verlet's 1e-3 of the closed box (above) plus the error of the work's trapezoidal sum,
  // which over a whole impact cancels (a contact's force starts and ends at zero).
  EXPECT_LT(worst, 2e-3);
}

// Two seed-sized spheres (r 5 mm, Table 6's seed without rolling resistance) stacked on a floor
// under a servo lid that holds 200 N (the 200 kPa of the shear box on one force chain), stepped at
// `fraction` of the Rayleigh step. Walls: the floor is 0, the lid 1.
constexpr double kColumnRadius = 0.005, kColumnForce_n = 200.0, kLidSpeed = 0.1;

Simulation loaded_column(double fraction, const GuardOptions& guards = {}) {
  testing::MaterialSpec m = testing::table6_seed();
  m.rolling_friction = 0.0;
  const InteractionTable table = testing::make_table(m, 2e11, 0.3);
  constexpr double r = kColumnRadius;
  SimulationOptions opt = rayleigh_options(table, r, fraction);
  opt.guards = guards;
  Simulation sim(table, opt);
  BodyDef low = sphere_body(r, m.density_kg_m3, 0), high = low;
  low.position_m = Vec3(0, 0, r);
  high.position_m = Vec3(0, 0, 3.0 * r);
  sim.add_body(low);
  sim.add_body(high);
  sim.add_wall(testing::plane_wall(Vec3::Zero(), Vec3::UnitZ()));
  Wall lid = testing::plane_wall(Vec3(0, 0, 4.0 * r + 0.0005), -Vec3::UnitZ());
  lid.motion = std::make_shared<Servo>(-Vec3::UnitZ(), kColumnForce_n, kLidSpeed);
  sim.add_wall(lid);
  return sim;
}

// Two seed-sized spheres stacked on a floor under a servo lid that holds 200 N (the 200 kPa of the
// shear box on one force chain). Once the column is loaded the floor is taken away at once, as a
// force chain loses its footing when it buckles: the column springs apart and gives the elastic
// energy of its contacts back as motion. That is far above the old budget (a fall of one
// diameter, every body at the lid's speed) and within the lid's work: the guard lets it run, and
// the kinetic energy never exceeds the lid's work plus the potential energy released (energy
// balance; the dashpots and friction only take energy out).
TEST(Energy, ServoLoadedColumnSpringsApartWithinTheLidsWork) {
  Simulation sim = loaded_column(0.2);
  const auto& servo = dynamic_cast<const Servo&>(*sim.walls()[1].motion);
  const double dt = sim.options().dt_s, r = kColumnRadius;
  // Loaded: the lid holds its force to 1 %.
  ASSERT_TRUE(sim.run(static_cast<std::uint64_t>(0.03 / dt))) << sim.failure().message;
  ASSERT_NEAR(servo.measured_force_n(sim.walls()[1]) / kColumnForce_n, 1.0, 0.01);
  const double stored = sim.wall_work_j();
  sim.walls()[0].pose.origin_m.z() = -1.0;
  const double m_total = sim.bodies().mass_kg[0] + sim.bodies().mass_kg[1];
  const double old_limit =
      GuardOptions{}.max_energy_factor * (m_total * 9.81 * 2.0 * r + 0.5 * m_total * kLidSpeed * kLidSpeed);
  const double pe0 = sim.potential_energy_j(), w0 = sim.wall_work_j();
  double peak_ke = 0.0, worst_excess = -1.0;
  for (int k = 0; k < 200; ++k) {
    ASSERT_TRUE(sim.run(5)) << sim.failure().message;
    const double ke = sim.kinetic_energy_j(), released = pe0 - sim.potential_energy_j();
    peak_ke = std::max(peak_ke, ke);
    // The column's stored energy came from the lid's work before the drop (w0): the balance
    // counts the whole run's.
    worst_excess = std::max(worst_excess, (ke - released - sim.wall_work_j()) / w0);
  }
  std::printf("column loaded by the lid's work %.4e J; after the drop: peak kinetic energy %.4e J (old "
              "limit %.4e J), max (KE - released - W) / W %.3e\n", stored, peak_ke, old_limit, worst_excess);
  EXPECT_GT(peak_ke, old_limit);  // what the budget without the walls' work stopped
  // The energy balance; 1e-2 of the work: the trapezoidal sum's error while contacts are loaded.
  EXPECT_LT(worst_excess, 1e-2);
}

// The guard still stops a numerical blow-up while a lid works on the bed: the loaded column of
// the test above stepped at four times the Rayleigh step, beyond the explicit scheme's stable
// limit for its stiffest contact, gains energy geometrically, past the lid's work within a few
// hundred steps. (The guard is checked every step here, so the energy check comes before a
// non-finite value.)
TEST(Energy, GuardStopsABlowUpUnderAWorkingLid) {
  GuardOptions every_step;
  every_step.check_interval = 1;
  Simulation sim = loaded_column(4.0, every_step);
  EXPECT_FALSE(sim.run(100000));
  EXPECT_EQ(sim.failure().status, RunStatus::energy_runaway) << sim.failure().message;
  EXPECT_NE(sim.failure().message.find("the work the walls did"), std::string::npos) << sim.failure().message;
}

// A body's motion set between steps of a running simulation (Simulation::set_body_motion) takes a
// new energy reference at once: the guard goes on judging against it, not against none.
TEST(Energy, MotionSetMidRunKeepsTheGuardsReference) {
  Simulation sim = elastic_bed(six_cubed());
  ASSERT_TRUE(sim.run(10)) << sim.failure().message;
  sim.set_body_motion(0, Vec3(0.1, 0.0, 0.0), Vec3::Zero());
  EXPECT_TRUE(sim.run(1000)) << sim.failure().message;  // five energy checks
}

}  // namespace
}  // namespace seedcal
