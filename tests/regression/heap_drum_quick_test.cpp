// The piling and drum scenes at `quick` fidelity from the CLI (the two costly scenes, each its own
// ctest entry, tests/CMakeLists.txt, so that they run side by side): each writes its index with
// the run report, its raw data and its picture, and the index lies in a physically sensible
// range; the drum's angle rises with its speed where the bed turns with the shell. Their quick rigs
// against the paper rigs, with three seeds each, and the other trend checks are measured in
// docs/results/scenes.md and piling.md (too long for the suite).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "tests/support/cli.hpp"
#include "tests/support/scene_runs.hpp"

namespace seedcal {
namespace {

using testing::expect_out_files;
using testing::expect_run_report;
using testing::run_quick_scene;

TEST(PilingQuick, HeapHasASensibleAngle) {
  const auto j = run_quick_scene("piling", "--seed 1", "piling");
  expect_run_report(j);
  expect_out_files(j, {"piling_profile.csv", "piling.svg"});
  const double angle = j["angle_of_repose_deg"].get<double>();
  std::printf("piling quick: %.1f deg (laboratory 31.76, sd 1.16), %zu sectors, heap %.1f mm, %.0f CPU s\n", angle,
              j["sector_angles_deg"].size(), 1000.0 * j["heap_height_m"].get<double>(), j["cpu_seconds"].get<double>());
  // A heap of seeds with friction 0.55 stands between the angle of a loose frictional packing
  // and the steepest seed heaps (20 to 40 deg); every sector fitted, and the heap is at least four
  // seeds (9 mm) high, so that its side is a slope and not a step.
  EXPECT_GT(angle, 20.0);
  EXPECT_LT(angle, 40.0);
  EXPECT_EQ(j["sector_angles_deg"].size(), 8u);
  EXPECT_GT(j["heap_height_m"].get<double>(), 0.036);
  EXPECT_NE(j["stop_reason"].get<std::string>().find("settled"), std::string::npos) << j["stop_reason"];
}

TEST(DrumQuick, SurfaceHasASensibleAngleAndTheRigsNumbers) {
  const auto j = run_quick_scene("drum", "--seed 1", "drum");
  expect_run_report(j);
  expect_out_files(j, {"drum_surface.csv", "drum.svg"});
  const double angle = j["dynamic_angle_of_repose_deg"].get<double>();
  std::printf("drum quick, 5 rpm: %.1f deg (sd over the frames %.1f; the paper's simulation 43.80), %.0f CPU s\n", angle,
              j["dynamic_angle_frames_sd_deg"].get<double>(), j["cpu_seconds"].get<double>());
  // Froude number w^2 Rc / g at 5 rpm in a 200 mm drum, and the bed height of an 11.04 % fill:
  // (eps - sin eps cos eps) / pi = 0.1104 at eps = 0.8435 rad, h = Rc (1 - cos eps) = 33.5 mm.
  const double w = 5.0 * 2.0 * std::numbers::pi / 60.0;
  EXPECT_NEAR(j["froude_number"].get<double>(), w * w * 0.1 / 9.81, 1e-12);
  EXPECT_NEAR(j["fill_height_m"].get<double>(), 0.03351, 0.00001);
  ASSERT_EQ(j["frames"].size(), 3u);
  double ratio_sum = 0.0;
  int slipping = 0;
  for (const auto& f : j["frames"]) {
    EXPECT_GT(f["r2"].get<double>(), 0.8) << f.dump();
    // The wall layer moves between at rest (0) and with the shell (1); a slumping bed sliding
    // back may run against the turn for a moment, never faster than the shell.
    const double ratio = f["wall_layer_speed_ratio"].get<double>();
    EXPECT_GT(ratio, -1.0) << f.dump();
    EXPECT_LT(ratio, 1.2) << f.dump();
    ratio_sum += ratio;
    slipping += std::abs(ratio) < 0.1;
  }
  std::printf("drum quick, 5 rpm: wall layer at %.2f of the shell's speed, %d of 3 frames slipping\n",
              j["wall_layer_speed_ratio"].get<double>(), slipping);
  EXPECT_NEAR(j["wall_layer_speed_ratio"].get<double>(), ratio_sum / 3.0, 1e-12);
  EXPECT_EQ(j["slipping_frames"].get<int>(), slipping);
  // A slipping frame is said beside the index, with what to change.
  EXPECT_EQ(j.contains("warnings"), slipping > 0) << j.dump(1);
  if (slipping > 0) {  // it names the drum's material, whose friction with the seeds to raise
    EXPECT_NE(j["warnings"][0].get<std::string>().find("seeds and steel"), std::string::npos) << j["warnings"];
  }
  // A slowly turning drum: the surface stands above the static angle of repose and well below a
  // cataracting bed (with Table 6's seed-steel friction the bed slips on the shell once it has
  // tilted: docs/scenes/drum.md).
  EXPECT_GT(angle, 30.0);
  EXPECT_LT(angle, 55.0);
  EXPECT_EQ(j["stop_reason"], "all frames taken");
}

// The drum's angle rises with its speed: the shipped quick drum with every Table 6 value (nine-
// sphere seeds, seed-steel friction 0.4) and a shell of twelve flat plates, from slumping at 5 rpm
// (Froude number 2.8e-3) to cascading at 60 rpm (0.40), three seeds a speed, the angle read every
// 0.1 s over 1.5-3 s (a slumping bed swings by 10 deg between avalanches, so the mean needs many
// frames). The check is the trend study's own (`seedcal study trend`: more than 2 pooled sd, every
// step the expected way); the rise reads about 4.5 deg whether the frames span 1.5 s or 6 s
// (docs/results/drum.md).
//
// The twelve facets grip the seeds with their edges at Table 6's seed-steel friction, where the
// smooth shell lets the bed slip once it has tilted (docs/scenes/drum.md): at 5 rpm the wall layer
// moves with the shell on average (its speed ratio above 0.1, the scene's own threshold for a
// slipping frame), read from the trend's 5 rpm runs.
TEST(DrumSpeedTrend, AngleRisesFromSlumpingToCascading) {
  const std::string out = testing::scratch_dir("drum-speed-trend");
  std::string frames = "[1.5";
  for (int i = 1; i <= 15; ++i) frames += "," + std::to_string(1.5 + 0.1 * i).substr(0, 3);
  frames += "]";
  const auto r = testing::run_cli(
      "study trend --scene " + testing::source_dir() + "/data/scenes/jinong1/drum.toml" +
      " --set fidelity=quick --set drum.quick.shell_facets=12 --set 'drum.quick.frame_times_s=" +
      frames + "' --vary drum.quick.speed_rpm --levels 5 60 --repeats 3 --threads 1 --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto j = nlohmann::json::parse(testing::read_text(out + "/trend.json"));
  ASSERT_EQ(j["levels"].size(), 2u) << j.dump(1);
  const auto& lo = j["levels"][0]["index"];
  const auto& hi = j["levels"][1]["index"];
  std::printf("drum speed trend, Table 6, 12 facets: 5 rpm %.2f deg (sd %.2f), 60 rpm %.2f (sd %.2f), %.2f pooled sd\n",
              lo["mean"].get<double>(), lo["sd"].get<double>(), hi["mean"].get<double>(), hi["sd"].get<double>(),
              j["overall"]["difference_in_pooled_sd"].get<double>());
  EXPECT_EQ(lo["n"], 3);
  EXPECT_EQ(hi["n"], 3);
  EXPECT_TRUE(j["all_runs_ok"].get<bool>());
  EXPECT_TRUE(j["confirmed"].get<bool>()) << j["verdict"];
  EXPECT_GT(j["overall"]["difference_in_pooled_sd"].get<double>(), 2.0);
  // Between the heap's static angle and a bed thrown off the shell (centrifuging at Fr = 1).
  EXPECT_GT(lo["mean"].get<double>(), 25.0);
  EXPECT_LT(hi["mean"].get<double>(), 60.0);

  // The facets carry the bed at 5 rpm: every frame's surface is a line, the wall layer moves with
  // the shell on average over the three seeds.
  const auto& slow_runs = j["levels"][0]["runs"];
  ASSERT_EQ(slow_runs.size(), 3u);
  double ratio = 0.0;
  for (const auto& run : slow_runs) {
    EXPECT_EQ(run["shell_facets"], 12);
    for (const auto& f : run["frames"]) EXPECT_GT(f["r2"].get<double>(), 0.8) << f.dump();
    ratio += run["wall_layer_speed_ratio"].get<double>() / 3.0;
  }
  std::printf("drum quick, 12 facets, 5 rpm: wall layer at %.2f of the shell's speed (mean of seeds 1-3)\n", ratio);
  EXPECT_GT(ratio, 0.1);
}

}  // namespace
}  // namespace seedcal
