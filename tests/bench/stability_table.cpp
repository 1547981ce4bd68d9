// The measured stability table of docs/results/stability.md (a few minutes; not a test, so nothing here
// can pass or fail): for each corner of the parameter space and each step fraction, whether a run
// is refused, completes or fails, the restitution that comes out of an impact at each step count
// and over the contact's entry phase, and the settling bed at each fraction.
//   build/tests/stability_table > table.md
#include <algorithm>
#include <cstdio>
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

constexpr double kBox_m = 0.025, kBedTime_s = 0.4;

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

void print_header(const char* title, const std::vector<double>& fractions) {
  std::printf("\n%s\n\n| corner |", title);
  for (double f : fractions) std::printf(" %.2f |", f);
  std::printf("\n|---|");
  for (std::size_t i = 0; i < fractions.size(); ++i) std::printf("---|");
  std::printf("\n");
}

void impact_at_each_step_fraction() {
  print_header("Impact at 1.7155 m/s on steel (no gravity), rayleigh_fraction set explicitly:", kFractions);
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

void restitution_over_contact_entry_phases() {
  // dt = t_c / n exactly (t_c the elastic Hertz contact time, time_step.hpp), and the contact
  // starting at ten evenly spaced points within a step: the range of e_out / e - 1.
  std::printf("\nRestitution error over ten contact entry phases, 4 mm sphere on steel at 1.7155 m/s:\n\n"
              "| e | 10 steps | 15 steps | 20 steps | 50 steps | 1000 steps |\n|---|---|---|---|---|---|\n");
  const double v = 1.7155;
  for (double e : {0.01, 0.05, 0.1, 0.3, 0.65, 0.9, 1.0}) {
    Corner c = seed("sphere");
    c.shape = Shape::sphere;
    c.restitution = e;
    std::printf("| %g |", e);
    for (double n : {10.0, 15.0, 20.0, 50.0, 1000.0}) {
      const double dt = impact(c, {0.05, true}).dt_s * impact(c, {0.05, true}).steps_per_contact / n;
      double lo = 1e9, hi = -1e9;
      for (int k = 0; k < 10; ++k) {
        const Outcome o = impact(c, {0.0, true, dt}, v, (0.05 + 0.1 * k) * v * dt);
        lo = std::min(lo, o.restitution_out / e - 1.0);
        hi = std::max(hi, o.restitution_out / e - 1.0);
      }
      std::printf(" %+.1f .. %+.1f %% |", 100.0 * lo, 100.0 * hi);
    }
    std::printf("\n");
    std::fflush(stdout);
  }
}

void bed_at_each_step_fraction() {
  // From 0.1 up: a bed at 0.05 of the Rayleigh step takes a minute per corner; E >= 1e10 Pa,
  // density 100 kg/m3 and the 1:20 and 2,000-sphere clumps likewise (the stiff bed is run at the
  // default step by CornersThatMatterCompleteAtDefaultStep).
  const std::vector<double> fractions = {0.1, 0.2, 0.3, 0.5, 0.7, 1.0};
  print_header("Bed: nine-sphere seeds poured into a 25 mm steel box and settled:", fractions);
  std::vector<Corner> corners;
  for (const Corner& c : table_corners())
    if (c.shape == Shape::seed9 && c.youngs_modulus_pa >= 1e6 && c.youngs_modulus_pa < 1e10 &&
        c.density_kg_m3 > 100.0)
      corners.push_back(c);
  for (const Corner& c : corners) {
    std::printf("| %s |", c.name.c_str());
    for (double f : fractions) {
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

int main() {
  seedcal::stability::impact_at_each_step_fraction();
  seedcal::stability::restitution_over_contact_entry_phases();
  seedcal::stability::bed_at_each_step_fraction();
  return 0;
}
