// Response-surface tools against Montgomery, DAE 8th ed.:
//   Example 11.1 (sec. 11.2): path of steepest ascent from y = 40.44 + 0.775 x1 + 0.325 x2 with a
//     base step of 5 min in time (1 coded unit): dx2 = 0.325 / 0.775 = 0.42 coded = 2 F (Table 11.3);
//   Example 11.2 (sec. 11.3.1): stationary point x_s = (0.389, 0.306), y_s = 80.21, canonical form
//     y = 80.21 - 0.9634 w1^2 - 1.4141 w2^2 (a maximum); natural units 86.95 min, 176.53 F.
#include <gtest/gtest.h>

#include <cmath>

#include "doe/core/errors.hpp"
#include "doe/regression/anova.hpp"
#include "doe/rsm/steepest_ascent.hpp"
#include "doe/rsm/surface_optimum.hpp"

namespace seedcal::doe {
namespace {

void expect_printed(double got, double printed, int decimals, const std::string& what) {
  EXPECT_LE(std::fabs(got - printed), 0.5 * std::pow(10.0, -decimals) + 1e-12)
      << what << ": computed " << got << ", printed " << printed;
}

TEST(SteepestAscent, Example11_1PathAndStoppingRule) {
  Eigen::VectorXd b(2);
  b << 0.775, 0.325;
  SteepestAscentOptions o;
  o.max_steps = 12;
  const Eigen::VectorXd dx = steepest_step(b, o);
  EXPECT_DOUBLE_EQ(dx(0), 1.0);
  expect_printed(dx(1), 0.42, 2, "dx2 coded");
  // Natural units: time = 35 + 5 x1, temperature = 155 + 5 x2; the book rounds dx2 to 2 F.
  const Eigen::MatrixXd path = steepest_path(b, Eigen::VectorXd::Zero(2), o);
  ASSERT_EQ(path.rows(), 12);
  expect_printed(35 + 5 * path(0, 0), 40, 0, "time step 1");
  expect_printed(155 + 5 * path(0, 1), 157, 0, "temp step 1");
  expect_printed(35 + 5 * path(11, 0), 95, 0, "time step 12");
  // (The book then rounds the temperature step to 2 F, so its 12th point is 179 F; unrounded,
  // 155 + 12 * 2.097 = 180.2 F.)
  EXPECT_NEAR(155 + 5 * path(11, 1), 155 + 12 * 5 * 0.325 / 0.775, 1e-12);
  // Table 11.3 yields along the path: the book stops after two successive decreases (11 and 12 Delta)
  // and takes 10 Delta (85 min, 175 F; yield 80.3) as the next centre.
  const double yields[12] = {41.0, 42.9, 47.1, 49.7, 53.8, 59.9, 65.0, 70.4, 77.6, 80.3, 76.2, 75.1};
  int k = 0;
  const PathResult r = follow_path(b, Eigen::VectorXd::Zero(2), [&](const Eigen::VectorXd&) { return yields[k++]; }, o);
  EXPECT_EQ(r.best, 9);
  EXPECT_EQ(r.responses.size(), 12u);
  EXPECT_EQ(r.stop_reason, "no improvement");
  // Target stopping rule: stop as soon as the responses bracket 60.
  k = 0;
  o.has_target = true;
  o.target = 60.0;
  o.stop_after_worse = 5;
  const PathResult t = follow_path(b, Eigen::VectorXd::Zero(2), [&](const Eigen::VectorXd&) { return yields[k++]; }, o);
  EXPECT_EQ(t.responses.size(), 7u);
  EXPECT_EQ(t.stop_reason, "target bracketed");
  // Descent reverses the direction; a bound cuts the path.
  o.descent = true;
  o.bound = 3.0;
  const Eigen::MatrixXd d = steepest_path(b, Eigen::VectorXd::Zero(2), o);
  EXPECT_EQ(d.rows(), 3);
  EXPECT_DOUBLE_EQ(d(0, 0), -1.0);
}

TEST(SurfaceOptimum, Example11_2StationaryPointAndCanonicalForm) {
  Eigen::MatrixXd X(13, 2);
  const double s2 = std::sqrt(2.0);
  X << -1, -1, -1, 1, 1, -1, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, s2, 0, -s2, 0, 0, s2, 0, -s2;
  Eigen::VectorXd y(13);
  y << 76.5, 77.0, 78.0, 79.5, 79.9, 80.3, 80.0, 79.7, 79.8, 78.4, 75.6, 78.5, 77.0;
  const auto a = analyze_regression(X, y, model_terms(ModelKind::quadratic, {"x1", "x2"}));
  const QuadraticSurface s = quadratic_surface(a.terms, a.fit.coefficients);
  const CanonicalAnalysis c = canonical_analysis(s);
  expect_printed(c.stationary_point(0), 0.389, 3, "x1s");
  expect_printed(c.stationary_point(1), 0.306, 3, "x2s");
  expect_printed(c.stationary_response, 80.21, 2, "ys");
  expect_printed(c.eigenvalues(0), -1.4141, 4, "lambda (w2)");
  expect_printed(c.eigenvalues(1), -0.9634, 4, "lambda (w1)");
  EXPECT_EQ(c.nature, "maximum");
  expect_printed(85 + 5 * c.stationary_point(0), 86.95, 2, "time");
  expect_printed(175 + 5 * c.stationary_point(1), 176.53, 2, "temperature");
  // The bounded optimiser finds the same maximum inside the +-alpha box (NLopt xtol 1e-8 on x:
  // 1e-6 on x and the corresponding ~1e-12 on y leave room).
  SurfaceOptimizeOptions o;
  o.lower = Eigen::VectorXd::Constant(2, -s2);
  o.upper = Eigen::VectorXd::Constant(2, s2);
  const SurfaceOptimum m = optimize_surface(s, o);
  EXPECT_NEAR((m.x - c.stationary_point).norm(), 0.0, 1e-6);
  // Bounded away from it, the optimum sits on the boundary.
  o.upper << 0.2, 0.2;
  const SurfaceOptimum b = optimize_surface(s, o);
  EXPECT_NEAR(b.x(0), 0.2, 1e-9);
  EXPECT_NEAR(b.x(1), 0.2, 1e-9);
}

TEST(SurfaceOptimum, TargetSolutionSetAndSecondaryObjective) {
  // y = x1 + x2 on [0, 1]^2, target 1: the solution set is the diagonal x1 + x2 = 1. The default
  // secondary objective (distance to the box centre) picks (0.5, 0.5); "smallest x1" picks (0, 1).
  const Surface f = [](const Eigen::VectorXd& x) { return x(0) + x(1); };
  TargetOptions t;
  t.search.lower = Eigen::VectorXd::Zero(2);
  t.search.upper = Eigen::VectorXd::Ones(2);
  t.target = 1.0;
  t.tolerance = 1e-6;
  const TargetSolution r = solve_for_target(f, t);
  ASSERT_TRUE(r.found);
  EXPECT_TRUE(r.underdetermined);
  EXPECT_GE(r.solution_set.size(), 2u);
  for (const auto& x : r.solution_set) EXPECT_NEAR(f(x), 1.0, 1e-6);
  // COBYLA's constraint tolerance (1e-6 on |y - T|) bounds how far the choice can sit off the ideal.
  EXPECT_NEAR(r.chosen(0), 0.5, 1e-4);
  EXPECT_NEAR(r.chosen(1), 0.5, 1e-4);
  t.secondary = [](const Eigen::VectorXd& x) { return x(0); };
  const TargetSolution s = solve_for_target(f, t);
  EXPECT_NEAR(s.chosen(0), 0.0, 1e-4);
  EXPECT_NEAR(s.chosen(1), 1.0, 1e-4);
  // Unreachable target: not found, the closest point reported.
  t.target = 3.0;
  const TargetSolution u = solve_for_target(f, t);
  EXPECT_FALSE(u.found);
  EXPECT_NEAR(u.y, 2.0, 1e-6);
}

}  // namespace
}  // namespace seedcal::doe
