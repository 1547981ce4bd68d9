// End-to-end stability checks through `seedcal run` (docs/stability.md): no NaN ever reaches
// metrics.json, a run at the extremes either completes or exits with a message naming the
// parameter, and a rig too large for the machine's memory is refused up front with the estimate.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>

#include "tests/support/cli.hpp"

namespace seedcal {
namespace {

using testing::run_cli;

std::string scene(const std::string& name) {
  return testing::source_dir() + "/data/scenes/" + name + ".toml";
}

// Every number in the document is finite and nothing is null (nlohmann::json writes NaN and
// infinity as null); returns the path of the first offender, empty when clean.
std::string first_non_finite(const nlohmann::json& j, const std::string& path = "") {
  if (j.is_null()) return path + " (null)";
  if (j.is_number_float() && !std::isfinite(j.get<double>())) return path;
  if (j.is_object())
    for (const auto& [k, v] : j.items())
      if (auto p = first_non_finite(v, path + "." + k); !p.empty()) return p;
  if (j.is_array())
    for (std::size_t i = 0; i < j.size(); ++i)
      if (auto p = first_non_finite(j[i], path + "[" + std::to_string(i) + "]"); !p.empty()) return p;
  return "";
}

nlohmann::json metrics(const std::string& out) {
  return nlohmann::json::parse(testing::read_text(out + "/metrics.json"));
}

TEST(StabilityCli, ForcedUnstableRunsStopWithoutWritingNaN) {
  // Glass spheres at 10 m/s (data/scenes/examples/impact.toml, t_c ~ 40 us) forced to ever larger
  // steps, and a modulus of 1e15 Pa: each run completes or stops (exit 1) with a message; the
  // metrics file it writes holds finite numbers only.
  const std::vector<std::string> settings = {
      "--set dt_s=2e-6 --set force_dt=true",
      "--set dt_s=2e-5 --set force_dt=true",
      "--set dt_s=1e-4 --set force_dt=true",
      "--set materials.glass.youngs_modulus_pa=1e15 --set dt_s=1e-6 --set force_dt=true",
      // 20 steps: ended before the energy guard's first periodic check, and reported "ok" with
      // the spheres leaving at 42 km/s until scenes ran the guards once more at the end.
      "--set materials.glass.youngs_modulus_pa=1e15 --set dt_s=1e-5 --set force_dt=true",
      "--set materials.glass.youngs_modulus_pa=1e15 --set dt_s=1e-3 --set force_dt=true --set duration_s=1",
      "--set materials.glass.youngs_modulus_pa=1e15 --set dt_s=1e-4 --set force_dt=true --set duration_s=0.1",
  };
  int stopped = 0;
  std::vector<std::string> messages;
  for (std::size_t k = 0; k < settings.size(); ++k) {
    const std::string out = testing::scratch_dir("stability-nan-" + std::to_string(k));
    const auto r = run_cli("run " + scene("examples/impact") + " --threads 1 --out " + out + " " + settings[k]);
    ASSERT_TRUE(r.exit_code == 0 || r.exit_code == 1) << settings[k] << "\n" << r.output;
    const auto j = metrics(out);
    EXPECT_EQ(first_non_finite(j), "") << settings[k] << "\n" << j.dump(1);
    if (r.exit_code == 1) {
      ++stopped;
      EXPECT_NE(j["status"], "ok");
      EXPECT_FALSE(j["failure"]["message"].get<std::string>().empty());
      EXPECT_NE(r.output.find("the simulation stopped"), std::string::npos) << r.output;
      messages.push_back(j["failure"]["message"].get<std::string>());
    }
    // Every run this far past the limit must be stopped: a status "ok" here is a silent blow-up.
    if (k >= 3) {
      EXPECT_EQ(r.exit_code, 1) << settings[k] << "\n" << r.output;
    }
  }
  EXPECT_GE(stopped, 3);
  // A step above the Rayleigh step is named as the cause (not the modulus, which is huge here).
  bool names_step = false;
  for (const std::string& m : messages) names_step |= m.find("x the Rayleigh step") != std::string::npos;
  EXPECT_TRUE(names_step);
}

TEST(StabilityCli, StepAboveTheLimitIsRefusedNamingMaterialAndLimit) {
  const std::string out = testing::scratch_dir("stability-refuse");
  const auto r = run_cli("run " + scene("jinong1/free_drop") + " --threads 1 --out " + out +
                         " --set repeats=1 --set materials.seed.youngs_modulus_pa=1e11"
                         " --set rayleigh_fraction=1.0");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  for (const char* s : {"free_drop.toml", "rayleigh_fraction", "'seed' sphere", "E = 1e+11 Pa",
                        "use rayleigh_fraction <= ", "force_dt"})
    EXPECT_NE(r.output.find(s), std::string::npos) << s << "\n" << r.output;
  EXPECT_FALSE(std::filesystem::exists(out + "/metrics.json"));
}

TEST(StabilityCli, PhysicalRangeCornersCompleteAtTheDefaultStep) {
  // E = 1e6 Pa and density 20,000 kg/m3 need less than 0.2 of the Rayleigh step at the drop's
  // impact speed; the default fraction is lowered to the limit rather than refused. e = 0.01: the
  // seed comes to rest on the plate and the scene stops there.
  for (const std::string set : {"--set materials.seed.youngs_modulus_pa=1e6",
                                "--set materials.seed.density_kg_m3=20000",
                                "--set seed_steel.restitution=0.01"}) {
    const std::string out = testing::scratch_dir("stability-range");
    const auto r = run_cli("run " + scene("jinong1/free_drop") + " --threads 1 --out " + out +
                           " --set repeats=1 " + set);
    ASSERT_EQ(r.exit_code, 0) << set << "\n" << r.output;
    const auto j = metrics(out);
    EXPECT_EQ(first_non_finite(j), "") << set;
    EXPECT_EQ(j["status"], "ok");
    EXPECT_LE(j["max_energy_ratio"].get<double>(), 1.01) << set;  // stability_corners.hpp
    EXPECT_NE(j["stop_reason"], "max_time_s reached before the rebound apex") << set;
  }
}

TEST(StabilityCli, RigTooLargeForMemoryIsRefusedUpFrontWithTheEstimate) {
  // A 4 m cube of Jinong 1 seeds: about 1.3e8 nine-sphere seeds, over 1e9 spheres (a terabyte):
  // refused before anything is allocated, so in seconds, with exit code 2.
  const std::string out = testing::scratch_dir("stability-memory");
  const auto t0 = std::chrono::steady_clock::now();
  const auto r = run_cli("run " + scene("jinong1/bulk_density") + " --threads 1 --out " + out +
                         " --set fidelity=quick --set bulk_density.quick.container_m=[4.0,4.0,4.0]");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(r.exit_code, 2) << r.output;
  for (const char* s : {"bulk_density.toml", "container_m", "seeds", "spheres", "bytes", "GiB", "available"})
    EXPECT_NE(r.output.find(s), std::string::npos) << s << "\n" << r.output;
  EXPECT_LT(seconds, 30.0) << "the refusal should come before the pour";
  EXPECT_FALSE(std::filesystem::exists(out + "/metrics.json"));
}

}  // namespace
}  // namespace seedcal
