// The piling and drum scenes at `quick` fidelity from the CLI (the two costly scenes, each its own
// ctest entry, tests/CMakeLists.txt, so that they run side by side): each writes its index with
// the run report, its raw data and its picture, and the index lies in a physically sensible
// range. Their quick rigs against the paper rigs, with three seeds each, and the trend checks are
// measured in docs/scenes/README.md and piling.md (too long for the suite).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

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
  // A slowly turning drum: the surface stands above the static angle of repose and well below a
  // cataracting bed (with Table 6's seed-steel friction the bed slips on the shell once it has
  // tilted: docs/scenes/drum.md).
  EXPECT_GT(angle, 30.0);
  EXPECT_LT(angle, 55.0);
  EXPECT_EQ(j["stop_reason"], "all frames taken");
}

}  // namespace
}  // namespace seedcal
