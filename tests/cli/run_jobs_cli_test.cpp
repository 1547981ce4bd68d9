// End-to-end: `seedcal run --jobs N` runs a scene's repeats side by side and gives the series of
// one job: the same seeds, the same samples to the last bit, the files from the first seed, and a
// series that ends at its first failed run.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "tests/support/cli.hpp"

namespace seedcal {
namespace {

using testing::run_cli;

std::string free_drop() { return testing::source_dir() + "/data/scenes/jinong1/free_drop.toml"; }

nlohmann::json run_free_drop(const std::string& tag, const std::string& extra, int expected_exit = 0) {
  const std::string out = testing::scratch_dir(tag);
  const auto r = run_cli("run " + free_drop() + " --out " + out + " --seed 5 --set repeats=4 " + extra);
  EXPECT_EQ(r.exit_code, expected_exit) << r.output;
  auto j = nlohmann::json::parse(testing::read_text(out + "/metrics.json"));
  j["out_dir"] = out;
  return j;
}

TEST(RunJobsCli, RepeatsSideBySideGiveTheSeriesOfOneJob) {
  const auto one = run_free_drop("jobs-1", "--threads 1");
  const auto three = run_free_drop("jobs-3", "--jobs 3");
  EXPECT_EQ(one["provenance"]["jobs"], 1);
  EXPECT_EQ(three["provenance"]["jobs"], 3);
  EXPECT_EQ(three["provenance"]["threads"], 1);  // one thread a run unless told
  EXPECT_EQ(three["jobs"], 3);
  ASSERT_EQ(three["repeats"], 4);
  ASSERT_EQ(three["rebound_height_m_samples"].size(), 4u);
  // Bit for bit: each run depends on its seed and thread count only, not on the job that ran it.
  EXPECT_EQ(one["rebound_height_m_samples"], three["rebound_height_m_samples"]);
  EXPECT_EQ(one["rebound_height_m"], three["rebound_height_m"]);
  EXPECT_EQ(one["rebound_height_m_sd"], three["rebound_height_m_sd"]);
  ASSERT_EQ(three["runs"].size(), 4u);
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(three["runs"][k]["seed"], 5 + k);
    EXPECT_EQ(three["runs"][k]["steps"], one["runs"][k]["steps"]);
  }
  // The samples differ between seeds (random orientations), so a mix-up of seeds would show.
  EXPECT_NE(three["rebound_height_m_samples"][0], three["rebound_height_m_samples"][1]);
  // The CPU time is the runs' sum; the series' wall time is not, when they ran at once.
  double cpu = 0.0;
  for (const auto& r : three["runs"]) cpu += r["cpu_seconds"].get<double>();
  EXPECT_DOUBLE_EQ(three["cpu_seconds"].get<double>(), cpu);
  EXPECT_GT(three["wall_seconds"].get<double>(), 0.0);
  EXPECT_EQ(three["files_from_seed"], 5);
}

TEST(RunJobsCli, AFailedRunEndsTheSeriesAsInOneJob) {
  // A time step far above the stable one, forced: every run fails at impact, so the series holds
  // its first run only, however many ran at the same time.
  const std::string fail = "--set dt_s=1e-3 --set force_dt=true";
  const auto one = run_free_drop("jobs-fail-1", "--threads 1 " + fail, 1);
  const auto three = run_free_drop("jobs-fail-3", "--jobs 3 " + fail, 1);
  EXPECT_EQ(one["repeats"], 1);
  EXPECT_EQ(three["repeats"], 1);
  EXPECT_NE(three["status"], "ok");
  EXPECT_EQ(three["status"], one["status"]);
}

TEST(RunJobsCli, MoreThanOneThreadPerJobIsRefused) {
  const std::string out = testing::scratch_dir("jobs-threads");
  const auto r = run_cli("run " + free_drop() + " --out " + out + " --set repeats=2 --jobs 2 --threads 2");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  for (const char* s : {"--threads = 2", "--jobs = 2", "--threads 1"})
    EXPECT_NE(r.output.find(s), std::string::npos) << s << "\n" << r.output;
}

}  // namespace
}  // namespace seedcal
