// Miniatures of every scene kind, run end to end through the binary: the shipped Jinong 1 scenes
// with their protocols intact (pour, settle, the direct shear's servo-controlled lid and shear, the
// piling tube's lift, the bulk-density strike-off, the drum's rotation and frames, the free drop's
// repeats, the custom scene's hopper) on rigs a few seeds across, a tenth of the seed's Young's
// modulus (a 2.5x longer stable step, docs/time_step.md) and short times, and a two-rank MPI
// calibration of a two-sphere impact. They exist for the sanitizer stage (scripts/test.sh, stage 2:
// ASan, UBSan and LeakSanitizer), which leaves the quick-fidelity scene tests (label `slow`) out:
// every scene's code path runs there in seconds. They check that each run ends with exit 0, status
// ok and a finite index, not the index's value: a rig a few seeds across measures nothing a
// laboratory would (the regression tests and docs/scenes/ check the values at quick and paper
// fidelity).
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/cli.hpp"

namespace seedcal::testing {
namespace {

// A tenth of Table 6's Young's modulus: the overlaps stay far below the guard's (the miniatures'
// stresses are a few kPa but the direct shear's 200 kPa lid) and the step is 2.5x longer.
const std::string kSoft = " --set materials.seed.youngs_modulus_pa=1.65e7";

nlohmann::json run_mini(const std::string& scene, const std::string& sets, const std::string& tag,
                        int threads = 1) {
  const std::string out = scratch_dir("mini-" + tag);
  const auto r = run_cli("run " + source_dir() + "/data/scenes/jinong1/" + scene +
                         ".toml --set fidelity=quick --seed 1 --threads " + std::to_string(threads) + " --out " +
                         out + " " + sets);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  if (r.exit_code != 0 || !std::filesystem::exists(out + "/metrics.json")) return nullptr;
  auto j = nlohmann::json::parse(read_text(out + "/metrics.json"));
  EXPECT_EQ(j["status"], "ok") << j.dump(1);
  EXPECT_GT(j["steps"].get<double>(), 0.0);
  // The phases as they ran carry the plan's names in the plan's order (the plan's estimate and the
  // run's record are compared phase by phase, docs/results/cost_estimate.md).
  std::vector<std::string> ran, planned;
  for (const auto& p : j.value("phases", nlohmann::json::array())) ran.push_back(p.value("name", std::string()));
  for (const auto& p : j.value("plan", nlohmann::json::object()).value("phases", nlohmann::json::array()))
    planned.push_back(p.value("name", std::string()));
  EXPECT_FALSE(ran.empty()) << j.dump(1);
  EXPECT_EQ(ran, std::vector<std::string>(planned.begin(), planned.begin() + static_cast<std::ptrdiff_t>(std::min(ran.size(), planned.size()))))
      << "ran " << ::testing::PrintToString(ran) << ", planned " << ::testing::PrintToString(planned);
  std::filesystem::remove_all(out);
  return j;
}

void expect_finite(const nlohmann::json& j, const char* key) {
  ASSERT_FALSE(j.is_null());
  ASSERT_TRUE(j.contains(key)) << j.dump(1);
  EXPECT_TRUE(std::isfinite(j[key].get<double>())) << key << " = " << j[key];
}

TEST(ScenesMini, DirectShearWithItsServoLid) {
  // 9 seeds in a 30 mm box at the paper's 200 kPa, Table 6's stiffness (the lid's servo loop
  // runs against the real contact law), sheared 1 mm.
  const auto j = run_mini("direct_shear",
                          "--set direct_shear.quick.diameter_m=0.03 --set direct_shear.quick.sample_height_m=0.012"
                          " --set direct_shear.quick.shear_displacement_m=0.001"
                          " --set direct_shear.quick.shear_speed_m_s=0.05",
                          "ds");
  expect_finite(j, "shear_strength_pa");
}

TEST(ScenesMini, PilingWithItsLiftedTube) {
  const auto j = run_mini("piling",
                          "--set piling.quick.tube_diameter_m=0.035 --set piling.quick.fill_height_m=0.025"
                          " --set piling.quick.lift_speed_m_s=0.2 --set piling.quick.max_time_s=0.2" + kSoft,
                          "pi");
  expect_finite(j, "angle_of_repose_deg");
}

TEST(ScenesMini, BulkDensityContainer) {
  const auto j = run_mini("bulk_density",
                          "--set bulk_density.quick.container_m=[0.03,0.03,0.03]"
                          " --set bulk_density.quick.max_time_s=0.3" + kSoft,
                          "bd");
  expect_finite(j, "bulk_density_kg_m3");
}

TEST(ScenesMini, DrumOnTwoThreads) {
  // Two threads: the threaded contact pipeline and its reductions run under the sanitizers too.
  const auto j = run_mini("drum",
                          "--set drum.quick.diameter_m=0.06 --set drum.quick.depth_m=0.02"
                          " --set drum.quick.filling_rate=0.3 --set drum.quick.speed_rpm=30"
                          " --set drum.quick.frame_times_s=[0.2,0.3]" + kSoft,
                          "dr", 2);
  expect_finite(j, "dynamic_angle_of_repose_deg");
}

TEST(ScenesMini, FreeDropRepeats) {
  const auto j = run_mini("free_drop", "--set repeats=2" + kSoft, "fd");
  expect_finite(j, "rebound_height_m");
}

// The MPI executor with two ranks (rank 0 plans and writes the store, rank 1 runs every simulation)
// gives the local run's calibration value for value: each simulation is deterministic for its seed.
// The custom scene's hopper (data/scenes/examples/hopper.toml) with 10 g of seeds: the mesh, the
// cylinder and the sliding gate, the sink and every measurement, for a few tens of milliseconds.
TEST(ScenesMini, CustomHopper) {
  const std::string out = scratch_dir("mini-custom");
  const auto r = run_cli("run " + source_dir() +
                         "/data/scenes/examples/hopper.toml --set fidelity=quick --seed 1 --threads 1 --out " + out +
                         " --set custom.quick.fill_mass_kg=0.01 --set custom.quick.settle_max_time_s=0.02"
                         " --set custom.quick.run_time_s=0.04" + kSoft);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto j = nlohmann::json::parse(read_text(out + "/metrics.json"));
  EXPECT_EQ(j["status"], "ok") << j.dump(1);
  expect_finite(j, "hopper_final_kg");
  EXPECT_TRUE(std::filesystem::exists(out + "/custom.svg"));
  std::filesystem::remove_all(out);
}

TEST(ScenesMini, MpiCalibrationWithTwoRanksMatchesTheLocalOne) {
  if (std::system("command -v mpirun > /dev/null 2>&1") != 0) GTEST_SKIP() << "mpirun not installed";
  const std::string dir = scratch_dir("mini-mpi");
  const std::string study = source_dir() + "/tests/cli/mini/mpi_study.toml";
  const auto local = run_cli("calibrate " + study + " --out " + dir + "/local --threads 1 --quiet");
  ASSERT_EQ(local.exit_code, 0) << local.output;
  // Under the sanitizers (SEEDCAL_MPI_PRELOAD set by tests/CMakeLists.txt) the ranks keep Open MPI's
  // components mapped and unwind malloc's callers from DWARF (libc and Open MPI have no frame
  // pointers), so that every leak's stack names its library and only tests/sanitize/lsan.supp's
  // MPI libraries are let through.
  std::string sanitize;
  if (const char* preload = std::getenv("SEEDCAL_MPI_PRELOAD")) {
    const char* asan = std::getenv("ASAN_OPTIONS");
    sanitize = "-x LD_PRELOAD=" + std::string(preload) + " -x ASAN_OPTIONS=" + (asan ? std::string(asan) + ":" : "") +
               "fast_unwind_on_malloc=0 ";
  }
  const std::string cmd = "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 mpirun --oversubscribe -n 2 " +
                          sanitize + seedcal_binary() + " calibrate " + study + " --out " + dir + "/mpi --threads 1 --quiet > " +
                          dir + "/mpi.log 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << read_text(dir + "/mpi.log");
  const auto a = nlohmann::json::parse(read_text(dir + "/local/summary.json"));
  const auto b = nlohmann::json::parse(read_text(dir + "/mpi/summary.json"));
  EXPECT_EQ(a["calibrated"], b["calibrated"]);
  EXPECT_EQ(a["evaluations"], b["evaluations"]);
  EXPECT_EQ(a["confirmed"]["contact_duration_s"]["samples"], b["confirmed"]["contact_duration_s"]["samples"]);
  // The confirmed contact time meets the target within the study's tolerance (5 %).
  EXPECT_TRUE(b["confirmed"]["contact_duration_s"]["within_tolerance"].get<bool>()) << b["confirmed"].dump(1);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace seedcal::testing
