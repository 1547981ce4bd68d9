// The drum's wall-layer speed ratio (scenes/drum.hpp): 1 for a bed turning with the shell, 0 for a
// bed at rest under it, seeds away from the shell left out, and the fill-height formula's inverse.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "solver/scenes/drum.hpp"

namespace seedcal {
namespace {

// Bodies on a ring of radius rho in the x-z plane (the drum's axis is y), moving as a solid body
// turning at w about +y, plus `inner` bodies near the axis moving at `inner_speed` along +x.
BodyState ring(double rho, double w, int inner, double inner_speed) {
  BodyState b;
  for (int k = 0; k < 12; ++k) {
    const double a = 2.0 * std::numbers::pi * k / 12.0;
    const Vec3 p(rho * std::cos(a), 0.01 * k, rho * std::sin(a));
    b.position_m.push_back(p);
    b.velocity_m_s.push_back(w * Vec3::UnitY().cross(p));
    b.mass_kg.push_back(1e-3 * (1 + k % 3));
  }
  for (int k = 0; k < inner; ++k) {
    b.position_m.push_back(Vec3(0.01 * k, 0.0, -0.02));
    b.velocity_m_s.push_back(Vec3(inner_speed, 0.0, 0.0));
    b.mass_kg.push_back(1e-3);
  }
  return b;
}

TEST(DrumWallLayer, OneForABedTurningWithTheShellZeroForABedAtRest) {
  const double R = 0.1, d = 0.01, w = 15.0 * 2.0 * std::numbers::pi / 60.0;
  EXPECT_NEAR(wall_layer_speed_ratio(ring(R - 0.5 * d, w, 0, 0.0), R, d, w), 1.0, 1e-12);
  EXPECT_NEAR(wall_layer_speed_ratio(ring(R - 0.5 * d, 0.0, 0, 0.0), R, d, w), 0.0, 1e-12);
  // Half the shell's speed: one half.
  EXPECT_NEAR(wall_layer_speed_ratio(ring(R - 0.5 * d, 0.5 * w, 0, 0.0), R, d, w), 0.5, 1e-12);
  // Moving against the turn: negative.
  EXPECT_NEAR(wall_layer_speed_ratio(ring(R - 0.5 * d, -w, 0, 0.0), R, d, w), -1.0, 1e-12);
  // Seeds farther than one layer from the shell do not count, however they move.
  EXPECT_NEAR(wall_layer_speed_ratio(ring(R - 0.5 * d, w, 5, 3.0), R, d, w), 1.0, 1e-12);
  // No seed in the layer, or a drum at rest: 0.
  EXPECT_EQ(wall_layer_speed_ratio(ring(R - 3.0 * d, w, 0, 0.0), R, d, w), 0.0);
  EXPECT_EQ(wall_layer_speed_ratio(ring(R - 0.5 * d, w, 0, 0.0), R, d, 0.0), 0.0);
}

// A frame whose surface fit failed carries no angle: the mean and sd are over the measured frames
// and the failed one is counted (before, its 0 entered the mean and the count).
TEST(DrumFrames, MeanAndSdOverTheMeasuredFramesOnly) {
  DrumResult r;
  auto frame = [](double angle, bool ok) {
    DrumFrame f{};
    f.angle_deg = angle;
    f.fit.ok = ok;
    return f;
  };
  r.frames = {frame(40.0, true), frame(0.0, false), frame(44.0, true), frame(42.0, true)};
  summarize_frame_angles(r);
  EXPECT_EQ(r.measured_frames, 3);
  EXPECT_EQ(r.failed_frames, 1);
  EXPECT_DOUBLE_EQ(r.dynamic_angle_of_repose_deg, 42.0);
  EXPECT_DOUBLE_EQ(r.angle_sd_deg, 2.0);  // sqrt((4 + 4 + 0) / 2)
  r.frames = {frame(0.0, false)};
  summarize_frame_angles(r);
  EXPECT_EQ(r.measured_frames, 0);
  EXPECT_TRUE(std::isnan(r.dynamic_angle_of_repose_deg));  // no angle, not 0
}

TEST(DrumFill, HeightGivesTheFillingRateBack) {
  const double R = 0.1;
  for (double f : {0.01, 0.1104, 0.3, 0.5, 0.8}) {
    const double h = drum_fill_height(R, f);
    const double eps = std::acos(1.0 - h / R);
    EXPECT_NEAR((eps - std::sin(eps) * std::cos(eps)) / std::numbers::pi, f, 1e-12) << f;
  }
  EXPECT_NEAR(drum_fill_height(0.1, 0.1104), 0.0335, 5e-5);  // docs/scenes/drum.md: 33.5 mm
  EXPECT_NEAR(drum_fill_height(0.1, 0.5), 0.1, 1e-12);
}

}  // namespace
}  // namespace seedcal
