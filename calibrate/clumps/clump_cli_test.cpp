// End to end: `seedcal clump build|info|table` through the binary ($SEEDCAL_BINARY), exit codes and
// JSON keys, and a bad input (exit 2).
#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace {

struct Result {
  int rc;
  std::string out;
};

Result run(const std::string& args) {
  const char* bin = std::getenv("SEEDCAL_BINARY");
  const std::string cmd = std::string(bin ? bin : "build/seedcal") + " " + args + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  std::string out;
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), buf.size(), p)) out += buf.data();
  const int status = pclose(p);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

TEST(ClumpCli, BuildInfoJsonAndTable) {
  const std::string out = (std::filesystem::temp_directory_path() / "seedcal_cli_clump.toml").string();
  Result b = run("clump build --variety jinong1 --method manual --spheres 5 --out " + out);
  ASSERT_EQ(b.rc, 0) << b.out;
  Result i = run("clump info " + out + " --json");
  ASSERT_EQ(i.rc, 0) << i.out;
  const auto j = nlohmann::json::parse(i.out);
  for (const char* k : {"spheres", "volume_m3", "target_volume_m3", "iou", "principal_inertia_kg_m2", "bounding_box_m"})
    EXPECT_TRUE(j.contains(k)) << k;
  EXPECT_EQ(j["spheres"].get<int>(), 5);
  EXPECT_GE(j["iou"].get<double>(), 0.8);
  EXPECT_EQ(j["principal_inertia_kg_m2"].size(), 3u);
  Result t = run("clump table --variety jinong3 --json");
  ASSERT_EQ(t.rc, 0) << t.out;
  const auto tj = nlohmann::json::parse(t.out);
  ASSERT_EQ(tj["rows"].size(), 6u);
  // The bar: the finest automatic model within 10 % of the paper's volume (the ellipsoid of the
  // Table 1 means is itself 5.4 % off the paper's scanned seed, docs/clumps.md), manual ones
  // within 15 % and IoU >= 0.8. Both kinds must be there: a renamed label fails, not passes.
  int finest = 0, manual = 0;
  for (const auto& row : tj["rows"]) {
    if (row["request"] == "--method auto --smoothness 0") {
      ++finest;
      EXPECT_NEAR(row["volume_vs_paper"].get<double>(), 1.0, 0.10);
    }
    if (row["filling"] == "manual") {
      ++manual;
      EXPECT_NEAR(row["volume_vs_paper"].get<double>(), 1.0, 0.15);
      EXPECT_GE(row["iou"].get<double>(), 0.8);
    }
  }
  EXPECT_EQ(finest, 1) << tj.dump(1);
  EXPECT_EQ(manual, 3) << tj.dump(1);  // the paper's manual counts for Jinong 3: 7, 9, 11
}

TEST(ClumpCli, BadInputExitsTwo) {
  EXPECT_EQ(run("clump build --variety jinong1 --method manual --spheres 8 --out /tmp/x.toml").rc, 2);
  EXPECT_EQ(run("clump build --variety nosuch --method auto --smoothness 1 --out /tmp/x.toml").rc, 2);
  EXPECT_EQ(run("clump info /nonexistent/clump.toml").rc, 2);
}

}  // namespace
