// End-to-end: `seedcal run` on impact scenes: exit codes, metrics keys, --set, bad input, missing
// interactions, the buried-sphere warning (and a drum
// rig key's bad input, refused before anything runs).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <filesystem>
#include <regex>

#include "tests/support/cli.hpp"

namespace seedcal {
namespace {

using testing::run_cli;

std::string example() { return testing::source_dir() + "/data/scenes/examples/impact.toml"; }

TEST(RunImpactCli, WritesMetricsWithEveryRequiredKey) {
  const std::string out = testing::scratch_dir("impact");
  const auto r = run_cli("run " + example() + " --out " + out + " --threads 1 --seed 3");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto j = nlohmann::json::parse(testing::read_text(out + "/metrics.json"));
  for (const char* k : {"contact_duration_s", "max_overlap_m", "max_normal_force_n", "max_contact_points",
                        "final", "cpu_seconds", "wall_seconds", "steps", "bodies", "spheres",
                        "stop_reason", "provenance"})
    EXPECT_TRUE(j.contains(k)) << k;
  ASSERT_EQ(j["final"].size(), 2u);
  for (const auto& b : j["final"])
    for (const char* k : {"position_m", "velocity_m_s", "angular_velocity_rad_s"}) EXPECT_TRUE(b.contains(k));
  EXPECT_EQ(j["bodies"], 2);
  EXPECT_EQ(j["provenance"]["seed"], 3);
  // Restitution 0.9 in the example: each sphere leaves at 4.5 m/s (0.1 %: dt = t_c / 4700).
  EXPECT_NEAR(j["final"][1]["velocity_m_s"][0].get<double>(), 4.5, 4.5e-3);
  EXPECT_EQ(j["max_contact_points"], 1);
}

TEST(RunImpactCli, SetOverridesANamedInteraction) {
  const std::string out = testing::scratch_dir("impact-set");
  const auto r = run_cli("run " + example() + " --out " + out + " --threads 1 --set glass_glass.restitution=0.5");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto j = nlohmann::json::parse(testing::read_text(out + "/metrics.json"));
  EXPECT_NEAR(j["final"][1]["velocity_m_s"][0].get<double>(), 2.5, 2.5e-3);
}

TEST(RunImpactCli, TimeStepAboveTheStableLimitIsRefused) {
  const std::string out = testing::scratch_dir("impact-dt");
  const auto r = run_cli("run " + example() + " --out " + out + " --set dt_s=1e-4");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("dt_s"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("stable limit"), std::string::npos) << r.output;
  // ... and runs when forced (then it is the user's responsibility).
  const auto f = run_cli("run " + example() + " --out " + out + " --set dt_s=2e-6 --set force_dt=true");
  EXPECT_EQ(f.exit_code, 0) << f.output;
}

TEST(RunImpactCli, BadInputNamesFileLineKeyValueAndRange) {
  const std::string dir = testing::scratch_dir("impact-bad");
  std::string text = testing::read_text(example());
  text = std::regex_replace(text, std::regex("poisson_ratio = 0.2"), "poisson_ratio = 0.7");
  text = std::regex_replace(text, std::regex("restitution = 0.9"), "restitusion = 0.9");
  testing::write_text(dir + "/bad.toml", text);
  const auto r = run_cli("run " + dir + "/bad.toml --out " + dir);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("bad.toml:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("materials.glass.poisson_ratio = 0.7: must be in [0, 0.5]"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("did you mean \"restitution\""), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("interaction[0].restitution is required"), std::string::npos) << r.output;
}

// A glass sphere falling on a steel plane with only a glass-glass interaction: without the check
// the sphere passes through the plane with zero force until the overlap guard blames the modulus.
TEST(RunImpactCli, WallMaterialWithoutAnInteractionIsRefused) {
  const std::string dir = testing::scratch_dir("impact-no-pair");
  testing::write_text(dir + "/drop.toml", R"(kind = "impact"
duration_s = 0.2
gravity_m_s2 = [0.0, 0.0, -9.81]
[materials.glass]
density_kg_m3 = 2800.0
youngs_modulus_pa = 4.8e10
poisson_ratio = 0.2
[materials.steel]
density_kg_m3 = 7800.0
youngs_modulus_pa = 2.0e11
poisson_ratio = 0.3
[[interaction]]
between = ["glass", "glass"]
restitution = 0.9
static_friction = 0.35
[[body]]
material = "glass"
radius_m = 0.01
position_m = [0.0, 0.0, 0.05]
[[wall]]
type = "plane"
material = "steel"
point_m = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
)");
  const auto r = run_cli("run " + dir + "/drop.toml --out " + dir + "/out");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("drop.toml"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("wall[0].material = \"steel\""), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("between = [\"glass\", \"steel\"]"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir + "/out/metrics.json"));
}

// Two bodies of different materials with an interaction only between each and itself.
TEST(RunImpactCli, BodyPairWithoutAnInteractionIsRefused) {
  const std::string dir = testing::scratch_dir("impact-no-body-pair");
  std::string text = testing::read_text(example());
  text += R"(
[materials.steel]
density_kg_m3 = 7800.0
youngs_modulus_pa = 2.0e11
poisson_ratio = 0.3
)";
  // The second body becomes steel: glass-steel has no interaction.
  const auto at = text.rfind("material = \"glass\"");
  text.replace(at, std::string("material = \"glass\"").size(), "material = \"steel\"");
  testing::write_text(dir + "/pair.toml", text);
  const auto r = run_cli("run " + dir + "/pair.toml --out " + dir + "/out");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("body[1].material = \"steel\""), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("between = [\"glass\", \"steel\"]"), std::string::npos) << r.output;
}

// A piling scene whose only seed interaction is with the steel: the seeds would pass through each
// other. Refused before anything runs, naming [particle] material. (The shipped scene names a
// variety, which supplies the seed-seed interaction; this one gives the seed's values itself.)
TEST(RunImpactCli, SeedSeedPairWithoutAnInteractionIsRefused) {
  const std::string dir = testing::scratch_dir("piling-no-seed-pair");
  std::string text = testing::read_text(testing::source_dir() + "/data/scenes/jinong1/piling.toml");
  text = std::regex_replace(text, std::regex(R"(\nvariety = "[^"]*")"), "");
  text += R"(
[materials.seed]
density_kg_m3 = 1340.0
youngs_modulus_pa = 1.65e8
poisson_ratio = 0.4

[[interaction]]
name = "seed_steel"
between = ["seed", "steel"]
restitution = 0.65
static_friction = 0.4

[[interaction]]
name = "steel_steel"
between = ["steel", "steel"]
restitution = 0.5
static_friction = 0.3

[particle]
material = "seed"
clump_file = ")" + testing::source_dir() + "/data/bench/clump9.txt\"\n";
  testing::write_text(dir + "/piling.toml", text);
  const auto r = run_cli("run " + dir + "/piling.toml --out " + dir + "/out --set fidelity=quick");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("piling.toml"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("particle.material = \"seed\": the seeds touch each other"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("between = [\"seed\", \"seed\"]"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir + "/out/metrics.json"));
}

// A clump with spheres wholly inside another runs, but the reader names them: on standard error and
// in metrics.json. A clump file written here: a 4 mm sphere holding a 1 mm one, and a third sphere
// reaching half its radius out.
TEST(RunImpactCli, BuriedSpheresAreNamedAsAWarning) {
  const std::string dir = testing::scratch_dir("buried-warning");
  testing::write_text(dir + "/buried.txt", "0 0 0 0.004\n0.001 0 0 0.001\n0.0035 0 0 0.001\n");
  const auto r = run_cli("run " + testing::source_dir() + "/data/scenes/jinong1/free_drop.toml --out " + dir +
                         "/out --set particle.clump_file=\\\"" + dir + "/buried.txt\\\"");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("seedcal: warning:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("1 of 3 spheres lie inside another sphere"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("sphere 2 (r = 0.001 m"), std::string::npos) << r.output;
  const auto j = nlohmann::json::parse(testing::read_text(dir + "/out/metrics.json"));
  ASSERT_TRUE(j.contains("warnings")) << j.dump(1);
  ASSERT_EQ(j["warnings"].size(), 1u);
  EXPECT_NE(j["warnings"][0].get<std::string>().find("in sphere 1 (r = 0.004 m"), std::string::npos) << j["warnings"];
}

TEST(RunImpactCli, DrumShellFacetsOutOfRangeExitTwo) {
  const std::string drum = testing::source_dir() + "/data/scenes/jinong1/drum.toml";
  for (const char* bad : {"2", "721", "12.5"}) {
    const auto r = run_cli("run " + drum + " --set fidelity=quick --set drum.quick.shell_facets=" + bad);
    EXPECT_EQ(r.exit_code, 2) << bad << ": " << r.output;
    EXPECT_NE(r.output.find("drum.toml"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("drum.quick.shell_facets"), std::string::npos) << r.output;
  }
  const auto r = run_cli("run " + drum + " --set fidelity=quick --set drum.quick.shell_facets=2");
  EXPECT_NE(r.output.find("allowed: 0 (a smooth shell) or 3 to 720 facets"), std::string::npos) << r.output;
}

TEST(RunImpactCli, MissingFileAndUnknownKindExitTwo) {
  EXPECT_EQ(run_cli("run /nonexistent/scene.toml").exit_code, 2);
  const std::string dir = testing::scratch_dir("impact-kind");
  testing::write_text(dir + "/k.toml", "kind = \"impakt\"\n");
  const auto r = run_cli("run " + dir + "/k.toml --out " + dir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("did you mean \"impact\""), std::string::npos) << r.output;
}

// `seedcal bench` prints its JSON on the last line, with the contact kernel's width; every width
// gives the same bed (the kernels give the same bits), and a width that is no kernel's exits 2.
TEST(RunImpactCli, BenchReportsKernelLanesAndTheSameBedAtEveryWidth) {
  std::vector<nlohmann::json> runs;
  for (const char* lanes : {"1", "8"}) {
    const auto r = run_cli(std::string("bench settled-bed --settle-steps 300 --timed-steps 30 "
                                       "--threads 1 --simd-lanes ") + lanes);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const std::string out = r.output.substr(0, r.output.find_last_not_of('\n') + 1);
    const auto j = nlohmann::json::parse(out.substr(out.find_last_of('\n') + 1));
    for (const char* k : {"sphere_steps_per_second", "spheres", "steps", "wall_seconds",
                          "contacts_per_sphere", "kernel_lanes", "seedcal_version", "seed"})
      EXPECT_TRUE(j.contains(k)) << k;
    EXPECT_EQ(j["spheres"], 10000);
    EXPECT_EQ(j["steps"], 30);
    runs.push_back(j);
  }
  EXPECT_EQ(runs[0]["kernel_lanes"], 1);
  const int wide = runs[1]["kernel_lanes"].get<int>();
  EXPECT_TRUE(wide == 1 || wide == 4 || wide == 8) << wide;
  EXPECT_EQ(runs[0]["contacts_per_sphere"], runs[1]["contacts_per_sphere"]);
  EXPECT_EQ(run_cli("bench settled-bed --simd-lanes 3").exit_code, 2);
}

// The fine clump bed (100 seeds of the 164-sphere automatic model) runs and says how its pairs
// were found; that both searches give the same list is solver_verlet_list_test's (a few steps
// here: the seeds meet after some 30,000, which the one-grid search takes too long for a test).
TEST(RunImpactCli, FineClumpBedRunsAndNamesItsPairSearch) {
  const auto r = run_cli(std::string("bench fine-clump-bed --settle-steps 200 --timed-steps 20 --threads 1 --clump-file ") +
                         testing::source_dir() + "/data/clumps/jinong1-auto-s2.toml --pair-search bodies");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string out = r.output.substr(0, r.output.find_last_not_of('\n') + 1);
  const auto j = nlohmann::json::parse(out.substr(out.find_last_of('\n') + 1));
  EXPECT_EQ(j["spheres"], 16400);
  EXPECT_EQ(j["bodies"], 100);
  EXPECT_EQ(j["pair_search"], "bodies");
  EXPECT_GT(j["kinetic_energy_j"].get<double>(), 0.0);  // falling under gravity
  EXPECT_EQ(run_cli("bench fine-clump-bed --pair-search cells").exit_code, 2);
}

TEST(RunImpactCli, HelpOnEveryLevel) {
  EXPECT_EQ(run_cli("--help").exit_code, 0);
  EXPECT_EQ(run_cli("run --help").exit_code, 0);
}

}  // namespace
}  // namespace seedcal
