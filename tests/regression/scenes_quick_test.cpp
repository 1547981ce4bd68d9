// The seed scenes at `quick` fidelity from the CLI: each runs, writes its index under its stable
// key with the run report, its raw-data CSV and its picture; indices lie in physically sensible
// ranges; and shear strength rises with seed-seed static friction (3 seeds per point).
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "tests/support/scene_runs.hpp"

namespace seedcal {
namespace {

using testing::expect_out_files;
using testing::expect_run_report;
using testing::run_quick_scene;

TEST(ScenesQuick, DirectShearStrengthIsSensibleAtBothFrictions) {
  std::vector<double> lo, hi;
  for (int s = 1; s <= 3; ++s) {
    const auto a = run_quick_scene("direct_shear", "--seed " + std::to_string(s) + " --set seed_seed.static_friction=0.1", "ds-lo" + std::to_string(s));
    const auto b = run_quick_scene("direct_shear", "--seed " + std::to_string(s) + " --set seed_seed.static_friction=1.0", "ds-hi" + std::to_string(s));
    expect_run_report(a);
    expect_out_files(a, {"direct_shear_curve.csv", "direct_shear.svg"});
    // The lid holds the normal stress to 2 % on average during shear.
    EXPECT_NEAR(a["mean_normal_stress_pa"].get<double>() / 2e5, 1.0, 0.02);
    // The upper ring rests on the lower one and may lift (1-2 mm by 4.5 mm of travel on these
    // seeds), never by half a seed's thickness (7.9 mm), through which seeds would leak.
    for (const auto* r : {&a, &b}) {
      EXPECT_GE((*r)["upper_ring_lift_m"].get<double>(), 0.0);
      EXPECT_LT((*r)["upper_ring_lift_m"].get<double>(), 0.004);
      // Levelled by centroid at 20 mm, the consolidated specimen stands 20-22 mm (seeds 1-12 at
      // Table 6's values); part of its seeds reach across the split.
      EXPECT_GT((*r)["consolidated_height_m"].get<double>(), 0.018);
      EXPECT_LT((*r)["consolidated_height_m"].get<double>(), 0.025);
      EXPECT_GT((*r)["seeds_across_split"].get<int>(), 0);
      EXPECT_LT((*r)["seeds_across_split"].get<int>(), (*r)["seeds"].get<int>());
    }
    lo.push_back(a["shear_strength_pa"].get<double>());
    hi.push_back(b["shear_strength_pa"].get<double>());
  }
  auto mean = [](const std::vector<double>& v) { double m = 0; for (double x : v) m += x; return m / static_cast<double>(v.size()); };
  auto var = [&](const std::vector<double>& v) { double m = mean(v), s = 0; for (double x : v) s += (x - m) * (x - m); return s / static_cast<double>(v.size() - 1); };
  const double pooled = std::sqrt(0.5 * (var(lo) + var(hi)));
  std::printf("shear strength: mu 0.1 -> %.0f Pa, mu 1.0 -> %.0f Pa, pooled sd %.0f Pa\n", mean(lo), mean(hi), pooled);
  // Sensible: a stress ratio tau / sigma between 0.1 and 1.5 at 200 kPa.
  for (double x : lo) EXPECT_GT(x, 0.1 * 2e5);
  for (double x : hi) EXPECT_LT(x, 1.5 * 2e5);
  // The direction of the friction effect is printed, not asserted: the quick box holds ~100 seeds
  // in two layers, one run's strength scatters by tens of kPa, and at the 4 mm the failure rule
  // reads (GB/T 50123) interlock across the split, not sliding, carries it. Measured over six seeds
  // per level, mu_s 0.1 -> 1.0 moves the ZJ box's strength by -0.03 pooled sd (LIGGGHTS on the
  // same rig: at most 1.1 sd either way; docs/results/direct_shear.md): the sign on three seeds is
  // noise, and an assertion on it passes or fails with the seeds' draws.
  std::printf("friction effect %.0f Pa = %.2f pooled sd\n", mean(hi) - mean(lo), (mean(hi) - mean(lo)) / pooled);
}

TEST(ScenesQuick, DirectShearRingHeldAtItsHeightDoesNotLift) {
  const auto j = run_quick_scene("direct_shear", "--seed 1 --set direct_shear.quick.upper_ring_fixed=true", "ds-fixed");
  expect_run_report(j);
  EXPECT_EQ(j["upper_ring_lift_m"].get<double>(), 0.0);
  // Failure read at 4 mm (GB/T 50123): the peak of a curve that still rises lies at the limit.
  EXPECT_LE(j["displacement_at_peak_m"].get<double>(), 0.004);
  EXPECT_GT(j["shear_strength_pa"].get<double>(), 0.1 * 2e5);
}

TEST(ScenesQuick, BulkDensityIsSensible) {
  const auto j = run_quick_scene("bulk_density", "", "bd");
  expect_run_report(j);
  std::printf("bulk density %.1f kg/m3 (paper 680.75, sd 17.27)\n", j["bulk_density_kg_m3"].get<double>());
  // A random packing of seeds has a solid fraction between 0.4 and 0.7.
  EXPECT_GT(j["solid_fraction"].get<double>(), 0.4);
  EXPECT_LT(j["solid_fraction"].get<double>(), 0.7);
  expect_out_files(j, {"bulk_density.svg"});
}

TEST(ScenesQuick, FreeDropRepeatsReportMeanSdAndSamples) {
  const auto j = run_quick_scene("free_drop", "--set repeats=3", "fd");
  expect_run_report(j);
  ASSERT_EQ(j["rebound_height_m_samples"].size(), 3u);
  EXPECT_TRUE(j.contains("rebound_height_m_sd"));
  // Below the restitution bound e^2 h = 0.65^2 x 150 mm = 63 mm, above zero.
  EXPECT_GT(j["rebound_height_m"].get<double>(), 0.005);
  EXPECT_LT(j["rebound_height_m"].get<double>(), 0.0634);
}

}  // namespace
}  // namespace seedcal
