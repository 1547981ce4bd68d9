// The traced solution curve against curves known in closed form (a sloped line, a vertical line,
// two branches) and positions along it by arc length.
#include <gtest/gtest.h>

#include <cmath>

#include "doe/core/errors.hpp"
#include "doe/rsm/level_curve.hpp"

namespace seedcal::doe {
namespace {

// Bisection to 60 halvings of a 0.01 step: the roots are exact to rounding.
constexpr double kRootTolerance = 1e-12;

TEST(LevelCurve, SlopedLineAcrossTheBox) {
  // f = u2 - 0.5 u1 = 0.1: from (-1, -0.4) to (1, 0.6), length sqrt(2^2 + 1^2).
  const Surface f = [](const Eigen::VectorXd& u) { return u(1) - 0.5 * u(0); };
  const CurvePath c = trace_level_curve(f, 0.1);
  ASSERT_TRUE(c.usable());
  for (const auto& p : c.points()) EXPECT_NEAR(p(1) - 0.5 * p(0), 0.1, kRootTolerance);
  EXPECT_NEAR(c.length(), std::sqrt(5.0), kRootTolerance * 10);
  EXPECT_NEAR(c.at(0.0)(0), -1.0, kRootTolerance);  // oriented along the first factor
  EXPECT_NEAR(c.at(1.0)(1), 0.6, kRootTolerance);
  EXPECT_NEAR(c.at(0.5)(0), 0.0, 1e-9);
  EXPECT_NEAR(c.at(0.5)(1), 0.1, 1e-9);
  // A point off the curve projects onto its foot: (0, 0.1) + t (-0.5, 1) / |.|, t = 0.3.
  const Eigen::Vector2d foot(0.0, 0.1), normal = Eigen::Vector2d(-0.5, 1.0).normalized();
  EXPECT_NEAR(c.project(foot + 0.3 * normal), 0.5, 1e-9);
  EXPECT_NEAR(c.project(Eigen::Vector2d(5.0, 5.0)), 1.0, 1e-12);  // beyond the end: the end
}

TEST(LevelCurve, SteepCurveIsTracedAsDenselyAsAFlatOne) {
  // u1 = 0.3 for every u2: scans at constant u1 find no sign change except on their own line; the
  // scans at constant u2 find the curve on every one of their 41 lines.
  const Surface f = [](const Eigen::VectorXd& u) { return u(0); };
  const CurvePath c = trace_level_curve(f, 0.3);
  ASSERT_TRUE(c.usable());
  EXPECT_GE(c.points().size(), 41u);
  EXPECT_NEAR(c.length(), 2.0, 1e-9);
  EXPECT_NEAR(c.at(0.25)(1), -0.5, 1e-9);
}

TEST(LevelCurve, KeepsTheBranchNearestTheAnchor) {
  // u1^2 = 0.25: two vertical branches at u1 = -0.5 and 0.5, a whole coded unit apart.
  const Surface f = [](const Eigen::VectorXd& u) { return u(0) * u(0); };
  LevelCurveOptions o;
  o.anchor = Eigen::Vector2d(0.4, 0.0);
  const CurvePath c = trace_level_curve(f, 0.25, o);
  ASSERT_TRUE(c.usable());
  for (const auto& p : c.points()) EXPECT_NEAR(p(0), 0.5, kRootTolerance);
  o.anchor = Eigen::Vector2d(-0.9, 0.9);
  const CurvePath other = trace_level_curve(f, 0.25, o);
  ASSERT_TRUE(other.usable());
  for (const auto& p : other.points()) EXPECT_NEAR(p(0), -0.5, kRootTolerance);
}

TEST(LevelCurve, NoCrossingGivesNoCurve) {
  const Surface f = [](const Eigen::VectorXd& u) { return 2.0 + u(0); };
  EXPECT_FALSE(trace_level_curve(f, 0.0).usable());
}

}  // namespace
}  // namespace seedcal::doe
