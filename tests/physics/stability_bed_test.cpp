// Stability of a settling bed (the bulk_density scene in a small box) at the corners that matter
// for sustained contacts. The measured table of docs/results/stability.md is printed by
// tests/bench/stability_table.cpp (build/tests/stability_table).
#include <gtest/gtest.h>

#include <algorithm>
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

}  // namespace
}  // namespace seedcal::stability
