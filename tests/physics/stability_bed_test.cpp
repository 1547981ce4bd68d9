// Stability of a settling bed (the bulk_density scene in a small box) at the corners that matter
// for sustained contacts, and the measured table of docs/stability.md.
//
// The table (not run by default; a few minutes):
//   SEEDCAL_STABILITY_TABLE=1 build/tests/physics_stability_bed_test --gtest_filter='StabilityTable.*'
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "tests/physics/stability_corners.hpp"

namespace seedcal::stability {
namespace {

Corner seed(const std::string& name) {
  Corner c;
  c.name = name;
  return c;
}

std::string describe(const Corner& c, const Outcome& o) {
  return c.name + ": " + to_string(o.verdict) + " after " + std::to_string(o.steps) + " steps of " +
         std::to_string(o.dt_s) + " s (" + o.stop_reason + "); " + o.message;
}

// Bed corners: nine-sphere seeds poured into a 25 mm steel box and settled for at most 0.4 s.
constexpr double kBox_m = 0.025, kBedTime_s = 0.4;

TEST(StabilityBed, CornersThatMatterCompleteAtDefaultStep) {
  std::vector<Corner> corners;
  auto add = [&](const std::string& name, auto set) {
    Corner c = seed(name);
    set(c);
    corners.push_back(c);
  };
  add("Jinong 1 seed", [](Corner&) {});
  add("E 1e6 (soft)", [](Corner& c) { c.youngs_modulus_pa = 1e6; });
  add("E 1e10 (stiff)", [](Corner& c) { c.youngs_modulus_pa = 1e10; });
  add("e 1 (no damping)", [](Corner& c) { c.restitution = 1.0; });
  add("e 0.05", [](Corner& c) { c.restitution = 0.05; });
  add("mu 0, mu_r 0", [](Corner& c) { c.static_friction = 0.0; c.rolling_friction = 0.0; });
  add("mu 1.5, mu_r 1 epsd", [](Corner& c) {
    c.static_friction = 1.5;
    c.rolling_friction = 1.0;
    c.rolling = RollingModel::epsd;
  });
  add("density 20000", [](Corner& c) { c.density_kg_m3 = 20000.0; });
  for (const Corner& c : corners) {
    const Outcome o = bed(c, {}, kBox_m, kBedTime_s);
    std::printf("%-22s %-8s %7llu steps, solid fraction %.3f, %s\n", c.name.c_str(), to_string(o.verdict),
                static_cast<unsigned long long>(o.steps), o.restitution_out,
                o.verdict == Verdict::ok ? o.stop_reason.c_str() : o.message.c_str());
    EXPECT_EQ(o.verdict, Verdict::ok) << describe(c, o);
  }
}

// --- the measured table -------------------------------------------------------------------------

const std::vector<double> kFractions = {0.05, 0.1, 0.2, 0.3, 0.5, 0.7, 1.0};

// One cell: the explicit fraction's fate, and when refused what a forced run does.
std::string cell(const Outcome& set, const Outcome& forced) {
  auto fate = [](const Outcome& o) -> std::string {
    char buf[48];
    switch (o.verdict) {
      case Verdict::ok: return "ok";
      case Verdict::refused: return "refused";
      case Verdict::stopped:
        return o.message.find("not finite") != std::string::npos ? "NaN stop"
               : o.message.find("overlap") != std::string::npos  ? "overlap stop"
                                                                   : "energy stop";
      case Verdict::energy_gain:
        std::snprintf(buf, sizeof buf, "E +%.0f %%", 100.0 * (o.max_energy_ratio - 1.0));
        return buf;
      case Verdict::bad_index: return "bad index";
    }
    return "?";
  };
  if (set.verdict != Verdict::refused) return fate(set);
  return "R, forced " + fate(forced);
}

std::vector<Corner> table_corners() {
  std::vector<Corner> out;
  auto add = [&](const std::string& name, auto set) {
    Corner c = seed(name);
    set(c);
    out.push_back(c);
  };
  add("Jinong 1 seed (E 1.65e8, e 0.65)", [](Corner&) {});
  add("E 1e5 Pa", [](Corner& c) { c.youngs_modulus_pa = 1e5; });
  add("E 1e6 Pa", [](Corner& c) { c.youngs_modulus_pa = 1e6; });
  add("E 1e10 Pa", [](Corner& c) { c.youngs_modulus_pa = 1e10; });
  add("E 1e11 Pa", [](Corner& c) { c.youngs_modulus_pa = 1e11; });
  add("nu 0", [](Corner& c) { c.poisson_ratio = 0.0; });
  add("nu 0.49", [](Corner& c) { c.poisson_ratio = 0.49; });
  add("density 100", [](Corner& c) { c.density_kg_m3 = 100.0; });
  add("density 20000", [](Corner& c) { c.density_kg_m3 = 20000.0; });
  add("e 0.01", [](Corner& c) { c.restitution = 0.01; });
  add("e 1", [](Corner& c) { c.restitution = 1.0; });
  add("mu 0", [](Corner& c) { c.static_friction = 0.0; });
  add("mu 2", [](Corner& c) { c.static_friction = 2.0; });
  add("mu_r 1 CDT", [](Corner& c) { c.rolling_friction = 1.0; });
  add("mu_r 1 EPSD", [](Corner& c) { c.rolling_friction = 1.0; c.rolling = RollingModel::epsd; });
  add("1:20 radius ratio clump", [](Corner& c) { c.shape = Shape::ratio20; });
  add("2000-sphere clump", [](Corner& c) { c.shape = Shape::spheres2000; });
  return out;
}

void print_header(const char* title) {
  std::printf("\n%s\n\n| corner |", title);
  for (double f : kFractions) std::printf(" %.2f |", f);
  std::printf("\n|---|");
  for (std::size_t i = 0; i < kFractions.size(); ++i) std::printf("---|");
  std::printf("\n");
}

bool table_requested() {
  const char* v = std::getenv("SEEDCAL_STABILITY_TABLE");
  return v != nullptr && std::string(v) == "1";
}

TEST(StabilityTable, ImpactAtEachStepFraction) {
  if (!table_requested()) GTEST_SKIP() << "set SEEDCAL_STABILITY_TABLE=1 to measure the table";
  print_header("Impact at 1.7155 m/s on steel (no gravity), rayleigh_fraction set explicitly:");
  for (const Corner& c : table_corners()) {
    std::printf("| %s |", c.name.c_str());
    for (double f : kFractions) {
      const Outcome set = impact(c, {f, false});
      const Outcome forced = set.verdict == Verdict::refused ? impact(c, {f, true}) : set;
      std::printf(" %s |", cell(set, forced).c_str());
    }
    std::printf("\n");
    std::fflush(stdout);
  }
  // Steps per contact and the restitution that comes out, sphere r 4 mm, Jinong 1 seed on steel.
  std::printf("\nRestitution out (steps per contact) of a 4 mm sphere, forced where refused:\n\n| e set |");
  for (double f : kFractions) std::printf(" %.2f |", f);
  std::printf("\n|---|");
  for (std::size_t i = 0; i < kFractions.size(); ++i) std::printf("---|");
  std::printf("\n");
  for (double e : {0.01, 0.05, 0.1, 0.3, 0.65, 0.9, 1.0}) {
    Corner c = seed("sphere");
    c.shape = Shape::sphere;
    c.restitution = e;
    std::printf("| %.2f |", e);
    for (double f : kFractions) {
      const Outcome o = impact(c, {f, true});
      std::printf(" %.4f (%.0f) |", o.restitution_out, o.steps_per_contact);
    }
    std::printf("\n");
  }
}

TEST(StabilityTable, BedAtEachStepFraction) {
  if (!table_requested()) GTEST_SKIP() << "set SEEDCAL_STABILITY_TABLE=1 to measure the table";
  print_header("Bed: nine-sphere seeds poured into a 25 mm steel box, settled up to 0.4 s:");
  std::vector<Corner> corners;
  for (const Corner& c : table_corners())
    if (c.shape == Shape::seed9 && c.youngs_modulus_pa < 1e11 && c.density_kg_m3 > 100.0) corners.push_back(c);
  for (const Corner& c : corners) {
    std::printf("| %s |", c.name.c_str());
    for (double f : kFractions) {
      const Outcome set = bed(c, {f, false}, kBox_m, kBedTime_s);
      const Outcome forced = set.verdict == Verdict::refused ? bed(c, {f, true}, kBox_m, kBedTime_s) : set;
      std::printf(" %s |", cell(set, forced).c_str());
    }
    std::printf("\n");
    std::fflush(stdout);
  }
}

}  // namespace
}  // namespace seedcal::stability
