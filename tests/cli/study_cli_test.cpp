// `seedcal study multicontact|stiffness|moisture|tradeoff|trend` end to end (the paper's section 4 studies, with
// few repeats so that the test takes seconds; docs/studies.md has the 10-repeat numbers).
#include <algorithm>
#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/cli.hpp"

namespace seedcal::testing {
namespace {

nlohmann::json run_study(const std::string& args, const std::string& dir, const std::string& kind) {
  const auto r = run_cli("study " + args + " --out " + dir + " --threads 1");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(dir + "/" + kind + ".csv"));
  EXPECT_NE(read_text(dir + "/report.html").find("<h2>"), std::string::npos) << "no studies report";
  return nlohmann::json::parse(read_text(dir + "/" + kind + ".json"));
}

// HMNR restores the set restitution for a clump landing on several spheres at once; plain HM adds
// the dampers of every contact in parallel, so the same drops (same seeds, same orientations)
// rebound lower. The paper: 58.0 mm vs 41.5 mm with its 188-sphere model.
TEST(StudyCli, MulticontactHmnrReboundsHigherThanHm) {
  const std::string dir = scratch_dir("study-multicontact");
  const auto j = run_study("multicontact --repeats 4", dir, "multicontact");
  const auto& fd = j["free_drop"];
  ASSERT_EQ(fd["hmnr"]["rebound_height_m"]["n"], 4) << fd.dump(1);
  ASSERT_EQ(fd["hertz_mindlin"]["rebound_height_m"]["n"], 4) << fd.dump(1);
  const auto hm = fd["hertz_mindlin"]["rebound_height_m"]["samples"].get<std::vector<double>>();
  const auto nr = fd["hmnr"]["rebound_height_m"]["samples"].get<std::vector<double>>();
  for (std::size_t i = 0; i < hm.size(); ++i) EXPECT_GT(nr[i], hm[i]) << "drop " << i;
  // Below the single-contact bound e^2 h = 0.65^2 x 150 mm = 63 mm, above a dead stop.
  EXPECT_LT(fd["hmnr"]["rebound_height_m"]["mean"].get<double>(), 0.0634);
  EXPECT_GT(fd["hertz_mindlin"]["rebound_height_m"]["mean"].get<double>(), 0.005);
  EXPECT_GE(fd["hmnr"]["contact_points"]["mean"].get<double>(), 1.0);
  EXPECT_FALSE(j.contains("drum"));
  EXPECT_EQ(j["provenance"]["seed"], 1);
  std::filesystem::remove_all(dir);
}

// Each Young's modulus is a row; a modulus too soft for the clump's smallest spheres stops with
// the deep-overlap guard and says so instead of writing a number.
TEST(StudyCli, StiffnessRowsReportEachModulus) {
  const std::string dir = scratch_dir("study-stiffness");
  const auto j = run_study("stiffness --repeats 2 --youngs-modulus-pa 1.65e6 1.65e8", dir, "stiffness");
  ASSERT_EQ(j["rows"].size(), 2u);
  for (const auto& r : j["rows"]) {
    if (r["status"] == "ok") {
      EXPECT_EQ(r["rebound_height_m"]["n"], 2) << r.dump(1);
      EXPECT_TRUE(r["rebound_height_m"]["mean"].is_number());
    } else {
      EXPECT_NE(r["failure"]["message"].get<std::string>().find("youngs_modulus_pa"), std::string::npos) << r.dump(1);
    }
  }
  EXPECT_EQ(j["rows"][1]["status"], "ok") << j.dump(1);
  // The verdict is the rows' own: the rebound of every completed modulus at least the previous
  // one's. (Whether it rises is the model's answer, not a fixed truth: the paper's Figure 26 says
  // it does, the tradeoff study measures the opposite on one clump, docs/studies.md.)
  std::vector<double> means;
  for (const auto& r : j["rows"])
    if (r["status"] == "ok") means.push_back(r["rebound_height_m"]["mean"].get<double>());
  bool rises = means.size() >= 2;
  for (std::size_t i = 1; i < means.size(); ++i) rises = rises && means[i] >= means[i - 1];
  EXPECT_EQ(j["rows_completed"].get<std::size_t>(), means.size()) << j.dump(1);
  EXPECT_EQ(j["rebound_rises_with_E"].get<bool>(), rises) << j.dump(1);
  const std::string csv = read_text(dir + "/stiffness.csv");
  EXPECT_EQ(csv.find("nan"), std::string::npos) << csv;
  std::filesystem::remove_all(dir);
}

// Table 3 and Table 2 of the paper for Jinong 1: the modulus falls with moisture, the seed grows
// on every axis with soaking.
TEST(StudyCli, MoistureFitsModulusAndSoaking) {
  const std::string dir = scratch_dir("study-moisture");
  const auto j = run_study("moisture --variety " + source_dir() + "/data/varieties/jinong1.toml", dir, "moisture");
  EXPECT_LT(j["log_linear_fit"]["c1"].get<double>(), 0.0);
  EXPECT_EQ(j["log_linear_fit"]["n"], 4);
  const double e = j["youngs_modulus_at_variety_moisture_pa"].get<double>();
  EXPECT_GT(e, 0.55e6);
  EXPECT_LT(e, 2.99e6 * 1.5);
  ASSERT_EQ(j["rows"].size(), 4u);
  for (const auto& r : j["rows"]) EXPECT_GT(r["volume_growth_ratio"].get<double>(), 1.0);
  std::filesystem::remove_all(dir);
}

// The speed-accuracy table on the free drop: four times the step fraction takes about a quarter
// of the steps; a hundred times softer seeds take a Rayleigh step ten times longer (dt_R ~ E^-1/2);
// the reference rows change by nothing, and every row says what it costs.
TEST(StudyCli, TradeoffRowsMeasureCostAndChange) {
  const std::string dir = scratch_dir("study-tradeoff");
  const auto j = run_study("tradeoff --scene " + source_dir() + "/data/scenes/jinong1/free_drop.toml" +
                               " --rayleigh-fractions 0.2 0.05 --youngs-modulus-pa 1.65e6 1.65e8 --repeats 2",
                           dir, "tradeoff");
  EXPECT_EQ(j["metric"], "rebound_height_m");
  ASSERT_EQ(j["sweeps"].size(), 2u);
  const auto& dt = j["sweeps"][0];
  const auto& stiff = j["sweeps"][1];
  ASSERT_EQ(dt["rows"].size(), 2u);
  ASSERT_EQ(stiff["rows"].size(), 2u);
  EXPECT_EQ(dt["reference"], 0.05);       // sorted: the finest step first
  EXPECT_EQ(stiff["reference"], 1.65e8);  // the stiffest first
  for (const auto* sw : {&dt, &stiff}) {
    const auto& ref = (*sw)["rows"][0];
    EXPECT_EQ(ref["relative_change"].get<double>(), 0.0) << ref.dump(1);
    EXPECT_EQ(ref["speedup"].get<double>(), 1.0);
    EXPECT_EQ(ref["index"]["n"], 2) << ref.dump(1);
    EXPECT_TRUE((*sw)["rows"][1]["relative_change"].is_number()) << sw->dump(1);
  }
  // The stiffest modulus at the scene's own step (0.2) is the step sweep's 0.2 row: not run twice.
  EXPECT_EQ(stiff["rows"][0]["same_runs_as"], "rayleigh_fraction = 0.2") << stiff.dump(1);
  EXPECT_EQ(stiff["rows"][0]["index"], dt["rows"][1]["index"]);
  const double steps_fine = dt["rows"][0]["steps_per_run"].get<double>();
  const double steps_coarse = dt["rows"][1]["steps_per_run"].get<double>();
  EXPECT_NEAR(steps_fine / steps_coarse, 4.0, 0.6) << dt.dump(1);
  EXPECT_GT(stiff["rows"][1]["dt_s"].get<double>(), 3.0 * stiff["rows"][0]["dt_s"].get<double>()) << stiff.dump(1);
  // The rig's size: the same container at every row, a clump of several spheres a seed.
  for (const auto& r : dt["rows"]) {
    EXPECT_GT(r["seeds_per_run"].get<double>(), 0.0) << r.dump(1);
    EXPECT_GT(r["spheres_per_run"].get<double>(), r["seeds_per_run"].get<double>()) << r.dump(1);
  }
  const std::string csv = read_text(dir + "/tradeoff.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 5) << csv;
  EXPECT_EQ(csv.find("nan"), std::string::npos) << csv;
  std::filesystem::remove_all(dir);
}

// The free drop's rebound rises with the seed-steel restitution (bounded by e^2 h): the trend
// check confirms it over the same three seeds per level, reads each step in pooled sd, and refuses
// to call a rise that the levels cannot show (a reversed expectation is not confirmed).
TEST(StudyCli, TrendConfirmsReboundRisesWithRestitution) {
  const std::string dir = scratch_dir("study-trend");
  const std::string scene = source_dir() + "/data/scenes/jinong1/free_drop.toml";
  const auto j = run_study("trend --scene " + scene + " --vary seed_steel.restitution --levels 0.3 0.6 0.9", dir, "trend");
  ASSERT_EQ(j["levels"].size(), 3u) << j.dump(1);
  ASSERT_EQ(j["steps"].size(), 2u);
  for (const auto& l : j["levels"]) EXPECT_EQ(l["index"]["n"], 3) << l.dump();
  const double lo = j["levels"][0]["index"]["mean"].get<double>(), hi = j["levels"][2]["index"]["mean"].get<double>();
  EXPECT_GT(hi, lo);
  EXPECT_NEAR(j["overall"]["difference"].get<double>(), hi - lo, 1e-12);
  // Pooled sample sd of the first and last level: sqrt((SS_a + SS_b) / (n_a + n_b - 2)).
  double ss = 0.0;
  for (int level : {0, 2}) {
    const auto& ix = j["levels"][level]["index"];
    for (const auto& x : ix["samples"]) ss += std::pow(x.get<double>() - ix["mean"].get<double>(), 2);
  }
  EXPECT_NEAR(j["overall"]["pooled_sd"].get<double>(), std::sqrt(ss / 4.0), 1e-12);
  EXPECT_GT(j["overall"]["difference_in_pooled_sd"].get<double>(), 2.0) << j["verdict"];
  EXPECT_TRUE(j["monotone"].get<bool>());
  EXPECT_TRUE(j["confirmed"].get<bool>()) << j["verdict"];
  EXPECT_NE(read_text(dir + "/report.md").find("Trend check"), std::string::npos);
  const auto r = run_study("trend --scene " + scene + " --vary seed_steel.restitution --levels 0.3 0.9 --expect fall",
                           scratch_dir("study-trend-fall"), "trend");
  EXPECT_FALSE(r["confirmed"].get<bool>()) << r["verdict"];
  EXPECT_FALSE(r["overall"]["expected_direction"].get<bool>());
  std::filesystem::remove_all(dir);
}

// --dry-run prints a line per level (its runs, the scene's plan and cost) and the total, and
// runs nothing.
TEST(StudyCli, TrendDryRunPrintsThePlanAndRunsNothing) {
  const std::string dir = scratch_dir("study-trend-dry");
  const auto r = run_cli("study trend --scene " + source_dir() + "/data/scenes/jinong1/free_drop.toml" +
                         " --vary seed_steel.restitution --levels 0.3 0.9 --repeats 3 --dry-run --threads 1 --out " + dir + "/out");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("plan: seed_steel.restitution=0.3, 3 runs (free_drop): 1 seeds"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("plan: seed_steel.restitution=0.9, 3 runs"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("plan: study trend: 6 DEM runs"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir + "/out")) << "a dry run wrote its output directory";
  // A bad level is still bad input.
  const auto bad = run_cli("study trend --scene " + source_dir() + "/data/scenes/jinong1/free_drop.toml" +
                           " --vary seed_steel.restitution --levels 0.3 1.5 --dry-run --out " + dir + "/out");
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("1.5"), std::string::npos) << bad.output;
  std::filesystem::remove_all(dir);
}

TEST(StudyCli, TrendOfAnUnknownKeyIsBadInput) {
  const auto r = run_cli("study trend --scene " + source_dir() + "/data/scenes/jinong1/free_drop.toml" +
                         " --vary seed_steel.restitutio --levels 0.3 0.9 --out " + scratch_dir("study-trend-bad"));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("restitutio"), std::string::npos) << r.output;
}

// Simulations run at once give the levels of one job (each run's seed is its own), and the
// provenance says how they ran. Each run's CPU time is its own thread's, not the process's: two
// runs at once would otherwise each count the other's time.
TEST(StudyCli, TrendWithTwoJobsGivesTheLevelsOfOne) {
  const std::string scene = source_dir() + "/data/scenes/jinong1/free_drop.toml";
  const std::string args = "trend --scene " + scene + " --vary seed_steel.restitution --levels 0.3 0.6 0.9 --repeats 2";
  const auto one = run_study(args, scratch_dir("study-trend-jobs1"), "trend");
  const auto two = run_study(args + " --jobs 2", scratch_dir("study-trend-jobs2"), "trend");
  ASSERT_EQ(one["levels"].size(), 3u);
  // Every field but the CPU time per run, which is measured.
  for (std::size_t i = 0; i < 3; ++i)
    EXPECT_EQ(one["levels"][i]["index"]["samples"], two["levels"][i]["index"]["samples"]) << i;
  EXPECT_EQ(two["jobs"], 2);
  EXPECT_EQ(two["provenance"]["jobs"], 2);
  EXPECT_EQ(one["verdict"], two["verdict"]);
  double cpu_one = 0.0, cpu_two = 0.0;
  for (std::size_t i = 0; i < 3; ++i) {
    cpu_one += one["levels"][i]["cpu_seconds_per_run"].get<double>();
    cpu_two += two["levels"][i]["cpu_seconds_per_run"].get<double>();
  }
  EXPECT_GT(cpu_two, 0.0);
  // Measured: within 10 % of one job's; a process clock read by two runs at once gives about 2x.
  EXPECT_LT(cpu_two, 1.5 * cpu_one) << "a run's CPU time includes the other job's";
  const auto r = run_cli("study " + args + " --jobs 2 --threads 2 --out " + scratch_dir("study-trend-jobs-threads"));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--threads 1"), std::string::npos) << r.output;
}

// A bad value at the last level is bad input before any level runs.
TEST(StudyCli, TrendChecksEveryLevelBeforeRunningAny) {
  const std::string dir = scratch_dir("study-trend-bad-level");
  const auto r = run_cli("study trend --scene " + source_dir() + "/data/scenes/jinong1/free_drop.toml" +
                         " --vary seed_steel.restitution --levels 0.3 0.6 1.5 --jobs 2 --threads 1 --out " + dir);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("restitution"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("1.5"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir + "/scenes")) << "a level ran before the check";
}

TEST(StudyCli, MissingSceneIsBadInput) {
  const auto r = run_cli("study multicontact --free-drop /nonexistent.toml --out " + scratch_dir("study-bad"));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("/nonexistent.toml"), std::string::npos) << r.output;
}

TEST(StudyCli, TradeoffMaterialMustBeInTheScene) {
  const auto r = run_cli("study tradeoff --scene " + source_dir() + "/data/scenes/jinong1/free_drop.toml --material cork" +
                         " --out " + scratch_dir("study-bad-material"));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("materials.cork.youngs_modulus_pa"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace seedcal::testing
