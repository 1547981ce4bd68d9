// The seed scenes at `quick` fidelity from the CLI: each runs, writes its index under its stable
// key with the run report, its raw-data CSV and its picture; indices lie in physically sensible
// ranges; and shear strength rises with seed-seed static friction (3 seeds per point).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "tests/support/cli.hpp"

namespace seedcal {
namespace {

using testing::run_cli;

// One thread per run: ctest runs two tests at once on two cores, and OpenMP threads that spin while
// the other test holds the core made a quick shear several times slower (README, "Threads").
nlohmann::json run_scene(const std::string& scene, const std::string& extra, const std::string& tag) {
  const std::string out = testing::scratch_dir(tag);
  const auto r = run_cli("run " + testing::source_dir() + "/data/scenes/jinong1/" + scene +
                         ".toml --set fidelity=quick --threads 1 --out " + out + " " + extra);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  auto j = nlohmann::json::parse(testing::read_text(out + "/metrics.json"));
  j["out_dir"] = out;
  return j;
}

void expect_report(const nlohmann::json& j) {
  for (const char* k : {"cpu_seconds", "wall_seconds", "steps", "bodies", "spheres", "stop_reason", "provenance"})
    EXPECT_TRUE(j.contains(k)) << k;
  EXPECT_EQ(j["status"], "ok");
}

TEST(ScenesQuick, DirectShearStrengthIsSensibleAndRisesWithFriction) {
  std::vector<double> lo, hi;
  for (int s = 1; s <= 3; ++s) {
    const auto a = run_scene("direct_shear", "--seed " + std::to_string(s) + " --set seed_seed.static_friction=0.1", "ds-lo" + std::to_string(s));
    const auto b = run_scene("direct_shear", "--seed " + std::to_string(s) + " --set seed_seed.static_friction=1.0", "ds-hi" + std::to_string(s));
    expect_report(a);
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
  // The quick box holds ~110 seeds in two layers, so one run's strength scatters by ~13 kPa. With
  // the end-of-step dashpot velocity (contact/hertz_mindlin.hpp) the friction effect from mu 0.1
  // to 1.0 measures +11 kPa on seeds 1-3 (75.2 -> 86.4 kPa, pooled sd 13.0 kPa): the direction is
  // asserted on these fixed seeds (deterministic for a seed and a thread count); one or two pooled
  // sd would take more seeds than a test can afford at this rig's scatter.
  std::printf("friction effect %.0f Pa = %.2f pooled sd\n", mean(hi) - mean(lo), (mean(hi) - mean(lo)) / pooled);
  EXPECT_GT(mean(hi), mean(lo));
}

TEST(ScenesQuick, BulkDensityIsSensible) {
  const auto j = run_scene("bulk_density", "", "bd");
  expect_report(j);
  std::printf("bulk density %.1f kg/m3 (paper 680.75, sd 17.27)\n", j["bulk_density_kg_m3"].get<double>());
  // A random packing of seeds has a solid fraction between 0.4 and 0.7.
  EXPECT_GT(j["solid_fraction"].get<double>(), 0.4);
  EXPECT_LT(j["solid_fraction"].get<double>(), 0.7);
  EXPECT_TRUE(std::filesystem::exists(j["out_dir"].get<std::string>() + "/bulk_density.svg"));
}

TEST(ScenesQuick, FreeDropRepeatsReportMeanSdAndSamples) {
  const auto j = run_scene("free_drop", "--set repeats=3", "fd");
  expect_report(j);
  ASSERT_EQ(j["rebound_height_m_samples"].size(), 3u);
  EXPECT_TRUE(j.contains("rebound_height_m_sd"));
  // Below the restitution bound e^2 h = 0.65^2 x 150 mm = 63 mm, above zero.
  EXPECT_GT(j["rebound_height_m"].get<double>(), 0.005);
  EXPECT_LT(j["rebound_height_m"].get<double>(), 0.0634);
}

}  // namespace
}  // namespace seedcal
