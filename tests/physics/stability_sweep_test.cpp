// Numerical stability at the extremes of every parameter (docs/stability.md): each corner either
// completes with bounded energy and sane indices, or stops with a message that names the
// parameter and the reason; inside the physical range (E 1e6-1e10 Pa, e 0.05-1, mu 0-1.5) every run
// completes at the default time step; a step above the stable limit is refused naming the limit;
// the restitution that comes out is the one set, from 0.01 to 1. Runs in-process through the
// impact and free_drop scenes (stability_corners.hpp); the bed corners and the measured table are
// in stability_bed_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "solver/core/errors.hpp"
#include "solver/scenes/impact.hpp"
#include "solver/sim/memory_estimate.hpp"
#include "solver/sim/particle_factory.hpp"
#include "solver/sim/time_step.hpp"
#include "tests/physics/stability_corners.hpp"

namespace seedcal::stability {
namespace {

// Relative tolerance of the restitution that comes out at n steps per (elastic Hertz) contact with
// the predicted dashpot velocity (ContactOptions::dashpot_predicted): 1.5 / n + 0.5 %. Where the
// contact starts within a step moves the outcome; over ten entry phases the largest error measured
// (docs/results/stability.md, "Restitution") was 14.4 % at 10 steps per contact (e = 0.05), 8.7 % at 15,
// 4.9 % at 20 and 1.6 % at 50, and below 0.1 % at 1,000: 1.5 / n bounds all of them; 0.5 % covers
// the rest.
double restitution_tolerance(double steps_per_contact) { return 1.5 / steps_per_contact + 0.005; }

// With the half-step dashpot velocity (the default) the damping force lags the force time by
// dt / 2: c v(t - dt/2) = c v(t) - (c dt / 2) a(t) + O(dt^2), and the part of -(c dt / 2) a that
// opposes v raises the damping ratio zeta by the factor 1 + zeta w dt. With w dt = pi / n (n steps
// over the contact's half period) and zeta <= -ln e / pi, ln e grows by at most the factor
// 1 - ln e / n: the restitution comes out low by up to 1 - exp(-(ln e)^2 / n) (0.88 at e = 0.01
// and 10 steps, 0.10 at e = 0.3 and 12, 0.02 at e = 0.65 and 12), on top of the tolerance above.
double half_step_tolerance(double e, double steps_per_contact) {
  const double l = std::log(e);
  return 1.0 - std::exp(-l * l / steps_per_contact) + restitution_tolerance(steps_per_contact);
}

double tolerance(const Corner& c, double e, double steps_per_contact) {
  return c.dashpot_predicted ? restitution_tolerance(steps_per_contact)
                             : half_step_tolerance(e, steps_per_contact);
}

Corner seed(const std::string& name) {
  Corner c;
  c.name = name;
  return c;
}

std::string describe(const Corner& c, const Outcome& o) {
  return c.name + " (" + to_string(c.shape) + "): " + to_string(o.verdict) + " after " +
         std::to_string(o.steps) + " steps of " + std::to_string(o.dt_s) + " s; " + o.message;
}

// --- inside the physical range: every run completes at the default time step -------------------

TEST(StabilitySweep, PhysicalRangeCompletesAtDefaultStep) {
  int runs = 0;
  for (Shape shape : {Shape::sphere, Shape::seed9})
    for (double E : {1e6, 1e7, 1e8, 1e9, 1e10})
      for (double e : {0.05, 0.5, 1.0})
        for (double mu : {0.0, 1.5}) {
          Corner c = seed("E " + std::to_string(E) + " e " + std::to_string(e) + " mu " + std::to_string(mu));
          c.shape = shape;
          c.youngs_modulus_pa = E;
          c.restitution = e;
          c.static_friction = mu;
          const Outcome o = impact(c, {});
          EXPECT_EQ(o.verdict, Verdict::ok) << describe(c, o);
          EXPECT_LE(o.max_energy_ratio, 1.0 + kEnergyGainBound) << describe(c, o);
          ++runs;
        }
  std::printf("%d impacts inside the physical range at the default step\n", runs);
}

TEST(StabilitySweep, EveryOtherParameterAtItsExtremesCompletesAtDefaultStep) {
  // Poisson 0-0.49, density 100-20,000 kg/m3, rolling friction 0-1 with CDT and EPSD, static
  // friction 0-2, on the seed clump at the stiff and the soft end of the modulus range (one
  // combination of two extremes goes past Hertz theory's range, below).
  std::vector<Corner> corners;
  for (double E : {1e6, 1e10}) {
    auto add = [&](const std::string& name, auto set) {
      Corner c = seed(name + ", E " + std::to_string(E));
      c.youngs_modulus_pa = E;
      set(c);
      corners.push_back(c);
    };
    add("nu 0", [](Corner& c) { c.poisson_ratio = 0.0; });
    add("nu 0.49", [](Corner& c) { c.poisson_ratio = 0.49; });
    add("density 100", [](Corner& c) { c.density_kg_m3 = 100.0; });
    add("density 20000", [](Corner& c) { c.density_kg_m3 = 20000.0; });
    add("mu 2", [](Corner& c) { c.static_friction = 2.0; });
    add("mu_r 0", [](Corner& c) { c.rolling_friction = 0.0; c.rolling = RollingModel::none; });
    add("mu_r 1 cdt", [](Corner& c) { c.rolling_friction = 1.0; c.rolling = RollingModel::cdt; });
    add("mu_r 1 epsd", [](Corner& c) { c.rolling_friction = 1.0; c.rolling = RollingModel::epsd; });
    add("hertz_mindlin", [](Corner& c) { c.normal = NormalModel::hertz_mindlin; });
  }
  for (const Corner& c : corners) {
    const Outcome o = impact(c, {});
    if (c.youngs_modulus_pa == 1e6 && c.density_kg_m3 == 20000.0) {
      // Soft and heavy together: Hertz theory puts the overlap of one of the clump's 1.75 mm
      // spheres at 2.5 mm at 1.7 m/s (time_step.hpp). The seed's spheres share the impact, so no
      // sphere's overlap passes its own radius (a clump sphere's limit, sim/guards.hpp) and the
      // run completes within the energy bound; it reports the overlap past half a radius, where
      // the force law is extrapolated beyond Hertz theory.
      std::printf("%s: deepest overlap %.3f of a sphere's radius\n", c.name.c_str(),
                  o.deepest_overlap_fraction);
      EXPECT_GT(o.deepest_overlap_fraction, 0.5) << describe(c, o);
      EXPECT_LE(o.deepest_overlap_fraction, 1.0) << describe(c, o);
    }
    EXPECT_EQ(o.verdict, Verdict::ok) << describe(c, o);
  }
}

TEST(StabilitySweep, ClumpOf2000SpheresReboundsWithTheSetRestitution) {
  // A 10 x 10 x 20 lattice block lands on a flat face: 100 or 200 sphere contacts at once. With
  // HMNR the pair keeps the set restitution (contact/normal_damping.hpp).
  Corner c = seed("2000 spheres");
  c.shape = Shape::spheres2000;
  const Outcome o = impact(c, {});
  ASSERT_EQ(o.verdict, Verdict::ok) << describe(c, o);
  std::printf("2000-sphere clump: e_out %.4f (set %.2f), %.0f steps per contact\n", o.restitution_out,
              c.restitution, o.steps_per_contact);
  EXPECT_NEAR(o.restitution_out / c.restitution, 1.0, tolerance(c, c.restitution, o.steps_per_contact));
}

// --- restitution out = restitution in, 0.01 to 1 ----------------------------------------------

TEST(StabilitySweep, RestitutionMatchesTheSetValueFrom001To1) {
  for (bool predicted : {false, true})
  for (double E : {1e6, 1.65e8, 1e10})
    for (double fraction : {0.0, 0.02})
      for (double e : {0.01, 0.02, 0.05, 0.1, 0.2, 0.3, 0.5, 0.7, 0.9, 1.0}) {
        Corner c = seed("sphere");
        c.shape = Shape::sphere;
        c.youngs_modulus_pa = E;
        c.restitution = e;
        c.dashpot_predicted = predicted;
        const Outcome o = impact(c, {fraction, false});
        ASSERT_EQ(o.verdict, Verdict::ok) << describe(c, o);
        const double tol = tolerance(c, e, o.steps_per_contact);
        const auto where = [&] {
          return "E " + std::to_string(E) + " e " + std::to_string(e) + " at " +
                 std::to_string(o.steps_per_contact) + " steps per contact, " +
                 (predicted ? "predicted" : "half-step") + " dashpot velocity";
        };
        // The half-step lag only adds damping: never above the set value by more than the
        // predicted velocity's tolerance; below it by at most `tol`, checked where that bound
        // says something (under 50 %: at the default step the lag leaves e <= 0.1 unresolved,
        // docs/stability.md, "Dashpot velocity").
        if (predicted || tol < 0.5) EXPECT_NEAR(o.restitution_out / e, 1.0, tol) << where();
        else EXPECT_LE(o.restitution_out / e, 1.0 + restitution_tolerance(o.steps_per_contact)) << where();
        if (e == 0.01 || e == 0.1 || e == 0.5)
          std::printf("%s dashpot, E %.3g Pa, %s step: e %.2f -> %.5f (%.0f steps per contact, tolerance %.1f %%)\n",
                      predicted ? "predicted" : "half-step", E,
                      fraction > 0.0 ? "0.02 Rayleigh" : "default", e, o.restitution_out,
                      o.steps_per_contact, 100.0 * tol);
      }
}

TEST(StabilitySweep, FreeDropReboundsWithTheSetRestitution) {
  // The free_drop scene itself (gravity, 150 mm, a 4 mm sphere on steel) at the default step: its
  // restitution_com is rebound over impact speed.
  Corner c = seed("sphere drop");
  c.shape = Shape::sphere;
  for (bool predicted : {false, true})
  for (double e : {0.01, 0.05, 0.1, 0.3, 0.65, 1.0}) {
    c.dashpot_predicted = predicted;
    c.restitution = e;
    const Outcome o = free_drop(c, {});
    ASSERT_EQ(o.verdict, Verdict::ok) << describe(c, o);
    // Steps per contact from Hertz theory (sim/time_step.hpp) at the impact speed.
    const BodyDef b = sphere_body(0.004, c.density_kg_m3, 0);
    const InteractionTable t({{"p", c.density_kg_m3, c.youngs_modulus_pa, c.poisson_ratio},
                              {"steel", 7850.0, 2e10, 0.3}},
                             {{"ps", 0, 1, e, c.static_friction, c.rolling_friction}});
    const double n = hertz_impact(b.mass_kg, 0.004, t.pair(0, 1).e_star_pa, std::sqrt(2 * 9.81 * 0.15))
                         .contact_time_s / o.dt_s;
    // Gravity acts during the contact too (the plate carries the weight as well as the impact):
    // it takes up to g t / v off the restitution, t the contact time, which damping stretches to
    // up to twice the elastic one (34 against 20 steps for e = 0.01 in the impact runs). For
    // e = 0.01 that is 0.0018, a fifth of the rebound.
    const double t_el = n * o.dt_s;
    const double gravity_share = 2.0 * 9.81 * t_el / std::sqrt(2 * 9.81 * 0.15);
    std::printf("%s dashpot: free drop e %.2f -> %.5f (%.0f steps per contact, gravity share %.4f)\n",
                predicted ? "predicted" : "half-step", e, o.restitution_out, n, gravity_share);
    EXPECT_NEAR(o.restitution_out, e, tolerance(c, e, n) * e + gravity_share)
        << "e = " << e << (predicted ? ", predicted" : ", half-step") << " dashpot velocity";
  }
}

// --- every corner: completes, or stops naming the parameter -------------------------------------

TEST(StabilitySweep, FreeDropCornersCompleteOrStopNamingTheCause) {
  struct Case {
    Corner corner;
    bool physical;          // inside the physical range: must complete
    std::string parameter;  // what a stop must name otherwise
  };
  std::vector<Case> cases;
  auto add = [&](const std::string& name, bool physical, const std::string& parameter, auto set) {
    Corner c = seed(name);
    set(c);
    cases.push_back({c, physical, parameter});
  };
  add("Jinong 1 seed", true, "", [](Corner&) {});
  add("E 1e5", false, "youngs_modulus_pa", [](Corner& c) { c.youngs_modulus_pa = 1e5; });
  add("E 1e6", true, "", [](Corner& c) { c.youngs_modulus_pa = 1e6; });
  add("e 0.01", false, "", [](Corner& c) { c.restitution = 0.01; });
  add("e 1", true, "", [](Corner& c) { c.restitution = 1.0; });
  add("mu 0", true, "", [](Corner& c) { c.static_friction = 0.0; });
  add("mu 2", false, "", [](Corner& c) { c.static_friction = 2.0; });
  add("mu_r 1 epsd", true, "", [](Corner& c) { c.rolling_friction = 1.0; c.rolling = RollingModel::epsd; });
  add("density 20000", true, "", [](Corner& c) { c.density_kg_m3 = 20000.0; });
  add("1:20 clump", false, "radius ratio 1:20", [](Corner& c) { c.shape = Shape::ratio20; });
  for (const Case& k : cases) {
    const Outcome o = free_drop(k.corner, {});
    std::printf("%-14s %-8s %7llu steps, energy ratio %.4f, e_com %.3f, %s\n", k.corner.name.c_str(),
                to_string(o.verdict), static_cast<unsigned long long>(o.steps), o.max_energy_ratio,
                o.restitution_out, o.verdict == Verdict::ok ? o.stop_reason.c_str() : o.message.c_str());
    if (k.physical || k.parameter.empty()) {
      EXPECT_EQ(o.verdict, Verdict::ok) << describe(k.corner, o);
    } else {
      EXPECT_TRUE(o.verdict == Verdict::ok || o.verdict == Verdict::stopped || o.verdict == Verdict::refused)
          << describe(k.corner, o);
      if (o.verdict != Verdict::ok) {
        EXPECT_NE(o.message.find(k.parameter), std::string::npos) << o.message;
      }
    }
    EXPECT_LE(o.max_energy_ratio, 1.0 + kEnergyGainBound) << describe(k.corner, o);
  }
}

// --- time step from 0.01 to 1 of the Rayleigh step ---------------------------------------------

TEST(StabilitySweep, ExplicitStepFractionsRunStablyOrAreRefused) {
  // Set explicitly, every fraction either runs cleanly or is refused up front: none blows up.
  std::vector<Corner> corners;
  for (double E : {1e5, 1e6, 1.65e8, 1e10, 1e11}) {
    Corner c = seed("E " + std::to_string(E));
    c.youngs_modulus_pa = E;
    corners.push_back(c);
  }
  for (double rho : {100.0, 20000.0}) {
    Corner c = seed("density " + std::to_string(rho));
    c.density_kg_m3 = rho;
    corners.push_back(c);
  }
  for (double e : {0.01, 1.0}) {
    Corner c = seed("e " + std::to_string(e));
    c.restitution = e;
    corners.push_back(c);
  }
  Corner epsd = seed("mu_r 1 epsd");
  epsd.rolling = RollingModel::epsd;
  epsd.rolling_friction = 1.0;
  corners.push_back(epsd);
  int refused = 0, ran = 0;
  for (const Corner& c : corners)
    for (double f : {0.01, 0.05, 0.1, 0.2, 0.3, 0.5, 0.7, 1.0}) {
      const Outcome o = impact(c, {f, false});
      if (o.verdict == Verdict::refused) {
        ++refused;
        EXPECT_EQ(o.refused_key, "rayleigh_fraction") << o.message;
        continue;
      }
      ++ran;
      // E = 1e5 Pa is outside the physical range: at 1.7 m/s its overlap passes half a radius
      // whatever the step, and the run stops saying so.
      if (c.youngs_modulus_pa < 1e6 && o.verdict == Verdict::stopped) {
        EXPECT_NE(o.message.find("youngs_modulus_pa"), std::string::npos) << o.message;
        continue;
      }
      EXPECT_EQ(o.verdict, Verdict::ok) << describe(c, o) << " at rayleigh_fraction " << f;
    }
  std::printf("%d runs, %d refused\n", ran, refused);
  EXPECT_GT(refused, 0);  // the sweep reaches past the limit
  EXPECT_GT(ran, refused);
}

// Parses the number after `prefix` in `text` (e.g. "use at most " -> 1.2e-07).
double number_after(const std::string& text, const std::string& prefix) {
  const std::size_t at = text.find(prefix);
  if (at == std::string::npos) return NAN;
  return std::stod(text.substr(at + prefix.size()));
}

TEST(StabilitySweep, RefusalNamesParameterMaterialAndAUsableLimit) {
  Corner c = seed("E 1e11");
  c.youngs_modulus_pa = 1e11;
  c.shape = Shape::sphere;
  // rayleigh_fraction = 1 at E = 1e11 Pa: refused, naming the key, the material and its modulus.
  const Outcome o = impact(c, {1.0, false});
  ASSERT_EQ(o.verdict, Verdict::refused) << describe(c, o);
  EXPECT_EQ(o.refused_key, "rayleigh_fraction");
  EXPECT_NE(o.message.find("E = 1e+11 Pa"), std::string::npos) << o.message;
  EXPECT_NE(o.message.find("'particle'"), std::string::npos) << o.message;
  const double limit = number_after(o.message, "use rayleigh_fraction <= ");
  ASSERT_TRUE(limit > 0.0 && limit < 1.0) << o.message;
  // The limit it gives is the real one: just below it runs, just above it is refused.
  EXPECT_EQ(impact(c, {0.99 * limit, false}).verdict, Verdict::ok);
  EXPECT_EQ(impact(c, {1.01 * limit, false}).verdict, Verdict::refused);
  // The same through dt_s: "use at most X s".
  ImpactSpec spec;
  spec.physics.materials = {{"particle", 1340.0, 1e11, 0.4}, {"steel", 7850.0, 2e10, 0.3}};
  spec.physics.interactions = {{"ps", 0, 1, 0.65, 0.4, 0.0}};
  spec.physics.gravity_m_s2 = Vec3::Zero();
  BodyDef b = sphere_body(0.004, 1340.0, 0);
  b.position_m = Vec3(0, 0, 0.0045);
  b.velocity_m_s = Vec3(0, 0, -1.7155);
  spec.bodies = {b};
  spec.walls = {ImpactWallSpec{Vec3::Zero(), Vec3::UnitZ(), 1}};
  spec.duration_s = 1e-3;
  spec.time_step.dt_s = 1e-5;
  try {
    run_impact(spec);
    FAIL() << "dt_s = 1e-5 s at E = 1e11 Pa was not refused";
  } catch (const SettingError& e) {
    EXPECT_EQ(e.key(), "dt_s");
    const double at_most = number_after(e.what(), "use at most ");
    ASSERT_GT(at_most, 0.0) << e.what();
    spec.time_step.dt_s = 0.99 * at_most;
    spec.duration_s = 100 * at_most;
    EXPECT_NO_THROW(run_impact(spec)) << e.what();
  }
}

// --- memory: refused up front with an estimate ---------------------------------------------------

TEST(StabilityMemory, EstimateGrowsWithSizeAndRefusesBeyondWhatIsAvailable) {
  const MemoryEstimate small = estimate_memory(1000, 9000, 1, false);
  const MemoryEstimate big = estimate_memory(100'000'000 / 9, 100'000'000, 1, false);
  // Per sphere of a nine-sphere clump: the state, lists and history add up to several hundred bytes
  // (memory_estimate.cpp); 1e8 spheres need tens of GiB.
  std::printf("per sphere %.0f bytes; 1e8 spheres: %s\n", small.total_bytes() / 9000.0, big.describe().c_str());
  EXPECT_GT(small.total_bytes() / 9000.0, 300.0);
  EXPECT_LT(small.total_bytes() / 9000.0, 3000.0);
  EXPECT_NEAR(big.total_bytes() / small.total_bytes(), 1e8 / 9000.0, 0.01 * 1e8 / 9000.0);
  EXPECT_GT(estimate_memory(1000, 9000, 1, true).total_bytes(), small.total_bytes());  // EPSD history
  EXPECT_NO_THROW(check_memory(small, 64.0 * (1ull << 30), "count", "small"));
  try {
    check_memory(big, 16.0 * (1ull << 30), "count", "1e8 spheres");
    FAIL() << "1e8 spheres in 16 GiB not refused";
  } catch (const SettingError& e) {
    EXPECT_EQ(e.key(), "count");
    EXPECT_NE(std::string(e.what()).find("GiB"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("1e+08 spheres"), std::string::npos) << e.what();
  }
  EXPECT_GT(available_memory_bytes(), 0.0);
}

TEST(StabilityMemory, FactoryRefusesAHundredMillionBodiesBeforeAllocating) {
  SimulationOptions opt;
  opt.dt_s = 1e-6;
  Simulation sim(InteractionTable({{"p", 1340.0, 1.65e8, 0.4}}, {{"pp", 0, 0, 0.5, 0.5, 0.0}}), opt);
  FactorySpec fs;
  fs.body = sphere_body(0.001, 1340.0, 0);
  fs.region.hi_m = Vec3(10.0, 10.0, 10.0);
  fs.count = 1'000'000'000;  // 1e9 spheres: over 500 GiB, more than any machine this runs on
  try {
    insert_particles(sim, fs);
    FAIL() << "1e9 bodies not refused";
  } catch (const SettingError& e) {
    EXPECT_EQ(e.key(), "count");
    EXPECT_NE(std::string(e.what()).find("bytes"), std::string::npos) << e.what();
    std::printf("%s\n", e.what());
  }
  EXPECT_EQ(sim.bodies().size(), 0u);
}

}  // namespace
}  // namespace seedcal::stability
