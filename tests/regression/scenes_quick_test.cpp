// The seed scenes at `quick` fidelity from the CLI: each runs, writes its index under its stable
// key with the run report, its raw-data CSV and its picture; indices lie in physically sensible
// ranges; and shear strength rises with seed-seed static friction (3 seeds per point).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "tests/support/scene_runs.hpp"

namespace seedcal {
namespace {

using testing::expect_run_report;
using testing::run_quick_scene;

TEST(ScenesQuick, DirectShearStrengthIsSensibleAndRisesWithFriction) {
  std::vector<double> lo, hi;
  for (int s = 1; s <= 3; ++s) {
    const auto a = run_quick_scene("direct_shear", "--seed " + std::to_string(s) + " --set seed_seed.static_friction=0.1", "ds-lo" + std::to_string(s));
    const auto b = run_quick_scene("direct_shear", "--seed " + std::to_string(s) + " --set seed_seed.static_friction=1.0", "ds-hi" + std::to_string(s));
    expect_run_report(a);
    EXPECT_TRUE(std::filesystem::exists(a["out_dir"].get<std::string>() + "/direct_shear_curve.csv"));
    EXPECT_TRUE(std::filesystem::exists(a["out_dir"].get<std::string>() + "/direct_shear.svg"));
    // The lid holds the normal stress to 2 % on average during shear.
    EXPECT_NEAR(a["mean_normal_stress_pa"].get<double>() / 2e5, 1.0, 0.02);
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
  // The quick box holds ~100 seeds in two layers, so one run's strength scatters by tens of kPa.
  // With CDT as static rolling friction (contact/rolling_cdt.hpp) the friction effect from mu 0.1
  // to 1.0 measures +99 kPa on seeds 1-3 (144 -> 243 kPa, pooled sd 62 kPa, 1.6 sd): the direction
  // is asserted on these fixed seeds (deterministic for a seed and a thread count); two pooled sd
  // would take a larger box than the laboratory's (`seedcal study trend` measures it with more
  // seeds, docs/scenes/direct_shear.md).
  std::printf("friction effect %.0f Pa = %.2f pooled sd\n", mean(hi) - mean(lo), (mean(hi) - mean(lo)) / pooled);
  EXPECT_GT(mean(hi), mean(lo));
}

TEST(ScenesQuick, BulkDensityIsSensible) {
  const auto j = run_quick_scene("bulk_density", "", "bd");
  expect_run_report(j);
  std::printf("bulk density %.1f kg/m3 (paper 680.75, sd 17.27)\n", j["bulk_density_kg_m3"].get<double>());
  // A random packing of seeds has a solid fraction between 0.4 and 0.7.
  EXPECT_GT(j["solid_fraction"].get<double>(), 0.4);
  EXPECT_LT(j["solid_fraction"].get<double>(), 0.7);
  EXPECT_TRUE(std::filesystem::exists(j["out_dir"].get<std::string>() + "/bulk_density.svg"));
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
