#pragma once
// Runs a shipped Jinong 1 scene at `quick` fidelity through the CLI and reads its metrics.json
// (with the output directory under "out_dir"), and checks the run report and the files every scene
// writes.
#include <gtest/gtest.h>

#include <filesystem>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/support/cli.hpp"

namespace seedcal::testing {

// One thread per run: ctest runs two tests at once on two cores, and OpenMP threads that spin while
// the other test holds the core made a quick shear several times slower (README, "Threads").
inline nlohmann::json run_quick_scene(const std::string& scene, const std::string& extra, const std::string& tag) {
  const std::string out = scratch_dir(tag);
  const auto r = run_cli("run " + source_dir() + "/data/scenes/jinong1/" + scene +
                         ".toml --set fidelity=quick --threads 1 --out " + out + " " + extra);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  auto j = nlohmann::json::parse(read_text(out + "/metrics.json"));
  j["out_dir"] = out;
  return j;
}

inline void expect_run_report(const nlohmann::json& j) {
  for (const char* k : {"cpu_seconds", "wall_seconds", "steps", "bodies", "spheres", "stop_reason", "provenance"})
    EXPECT_TRUE(j.contains(k)) << k;
  EXPECT_EQ(j["status"], "ok");
  // Each run's steps against its plan (solver/scenes/run_plan.hpp): `seedcal calibrate` promises a
  // cost estimate within a factor of 2 of the run (docs/calibrate.md, "Cost before work").
  const nlohmann::json runs = j.contains("runs") ? j["runs"] : nlohmann::json::array({j});
  for (const auto& r : runs) {
    ASSERT_TRUE(r.contains("plan")) << r.dump(1);
    const double ratio = r["steps"].get<double>() / r["plan"]["steps"].get<double>();
    EXPECT_GT(ratio, 0.5) << "steps " << r["steps"] << ", planned " << r["plan"].dump();
    EXPECT_LT(ratio, 2.0) << "steps " << r["steps"] << ", planned " << r["plan"].dump();
    // The phases as they ran, named and ordered as the plan's, account for every step and for no
    // more CPU time than the run's (the set-up before the first phase is the run's alone).
    ASSERT_TRUE(r.contains("phases")) << r.dump(1);
    ASSERT_EQ(r["phases"].size(), r["plan"]["phases"].size()) << r["phases"].dump() << r["plan"].dump();
    std::uint64_t steps = 0;
    double cpu = 0.0;
    for (std::size_t k = 0; k < r["phases"].size(); ++k) {
      EXPECT_EQ(r["phases"][k]["name"], r["plan"]["phases"][k]["name"]);
      EXPECT_GE(r["phases"][k]["simulated_s"].get<double>(), 0.0);
      steps += r["phases"][k]["steps"].get<std::uint64_t>();
      cpu += r["phases"][k]["cpu_seconds"].get<double>();
    }
    EXPECT_EQ(steps, r["steps"].get<std::uint64_t>());
    EXPECT_LE(cpu, r["cpu_seconds"].get<double>() * (1.0 + 1e-9));
  }
}

// The scene's raw data and picture exist in its output directory.
inline void expect_out_files(const nlohmann::json& j, std::initializer_list<const char*> names) {
  const std::string out = j["out_dir"];
  for (const char* n : names) EXPECT_TRUE(std::filesystem::exists(out + "/" + n)) << out << "/" << n;
}

}  // namespace seedcal::testing
