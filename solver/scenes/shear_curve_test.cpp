// Reading the shear box's curve (scenes/shear_curve.hpp) on made-up curves whose answers are known:
// the moving average of a constant and of a straight line, a spike spread over its window; the
// failure read at the peak or at the failure displacement; the curve's shape.
#include "solver/scenes/shear_curve.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace seedcal {
namespace {

// Samples every 0.1 mm up to `end_m`, the stress given by `tau(x)`.
template <class F>
std::vector<ShearSample> curve_of(double end_m, F tau) {
  std::vector<ShearSample> c;
  for (int k = 0; 1e-4 * k <= end_m + 1e-12; ++k) {
    const double x = 1e-4 * k;
    c.push_back({x, tau(x), 2e5, 0.0, 0.0, 0.0});
  }
  return c;
}

TEST(ShearCurve, MovingAverage) {
  auto flat = curve_of(0.004, [](double) { return 1e5; });
  smooth_curve(flat, 5e-4);
  for (const ShearSample& s : flat) EXPECT_DOUBLE_EQ(s.smoothed_shear_stress_pa, 1e5);
  // A centred average of a straight line is the line, away from the ends (whose windows are cut).
  auto line = curve_of(0.004, [](double x) { return 3e7 * x; });
  smooth_curve(line, 5e-4);
  for (const ShearSample& s : line) {
    if (s.displacement_m > 3e-4 && s.displacement_m < 0.0037) {
      EXPECT_NEAR(s.smoothed_shear_stress_pa, 3e7 * s.displacement_m, 1e-6) << s.displacement_m;
    }
  }
  // A spike at one sample is spread over the samples within half a window: 5 of them at 0.1 mm.
  auto spike = curve_of(0.004, [](double x) { return std::abs(x - 0.002) < 1e-9 ? 5e5 : 0.0; });
  smooth_curve(spike, 5e-4);
  EXPECT_NEAR(spike[20].smoothed_shear_stress_pa, 1e5, 1e-6);
}

TEST(ShearCurve, FailureIsThePeakOrTheStressAtTheFailureDisplacement) {
  // Peaks at 2 mm, then falls: the peak.
  auto peaked = curve_of(0.006, [](double x) { return 1e5 - 1e10 * (x - 0.002) * (x - 0.002); });
  smooth_curve(peaked, 5e-4);
  const ShearFailure p = read_failure(peaked, 0.00405);
  EXPECT_NEAR(p.displacement_m, 0.002, 1e-12);
  EXPECT_NEAR(p.shear_strength_pa, 1e5, 1e10 * 2.5e-4 * 2.5e-4);  // the average over the window
  // Still rising at the failure displacement (4.05 mm, between two samples): the stress at the
  // last sample before it, whatever comes after.
  auto rising = curve_of(0.006, [](double x) { return 3e7 * x; });
  smooth_curve(rising, 5e-4);
  const ShearFailure r = read_failure(rising, 0.00405);
  EXPECT_NEAR(r.displacement_m, 0.004, 1e-12);
  EXPECT_NEAR(r.shear_strength_pa, 1.2e5, 1e-6);
  EXPECT_EQ(read_failure({}, 0.004).shear_strength_pa, 0.0);
}

TEST(ShearCurve, Shape) {
  auto rising = curve_of(0.006, [](double x) { return 3e7 * x; });
  smooth_curve(rising, 5e-4);
  EXPECT_EQ(curve_shape(rising, 5e-4), "rising");
  auto peaked = curve_of(0.006, [](double x) { return 1e5 - 1e10 * (x - 0.002) * (x - 0.002); });
  smooth_curve(peaked, 5e-4);
  EXPECT_EQ(curve_shape(peaked, 5e-4), "peak");
  // Up to 2 mm, then nearly level (4 kPa lower by 6 mm): the end lies within twice the curve's
  // noise (set by its rise over one window, about 10 kPa) of the maximum.
  auto level = curve_of(0.006, [](double x) {
    return x < 0.002 ? 5e7 * x : 1e5 - 1e6 * (x - 0.002);
  });
  smooth_curve(level, 5e-4);
  EXPECT_EQ(curve_shape(level, 5e-4), "plateau");
}

}  // namespace
}  // namespace seedcal
