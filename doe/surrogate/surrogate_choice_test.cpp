// The choice of surrogate (surrogate_choice.hpp): a quadratic response is fitted by the quadratic,
// which then predicts out of sample to rounding; a response no quadratic follows goes to the GP;
// the caller's choice is kept; too few points for the quadratic leave the GP; the noise floor holds.
#include "doe/surrogate/surrogate_choice.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "doe/core/errors.hpp"

namespace seedcal::doe {
namespace {

// A 5 x 5 grid over the coded square [-1, 1]^2.
Eigen::MatrixXd grid() {
  Eigen::MatrixXd X(25, 2);
  int r = 0;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j) X.row(r++) << -1.0 + 0.5 * i, -1.0 + 0.5 * j;
  return X;
}

Eigen::VectorXd eval(const Eigen::MatrixXd& X, double (*f)(double, double)) {
  Eigen::VectorXd y(X.rows());
  for (Eigen::Index r = 0; r < X.rows(); ++r) y(r) = f(X(r, 0), X(r, 1));
  return y;
}

double quadratic(double a, double b) { return 1.0 + 2.0 * a - 3.0 * b + 0.5 * a * b + 4.0 * a * a - b * b; }
double wavy(double a, double b) { return std::sin(4.0 * a) * std::cos(3.0 * b); }

const std::vector<std::string> kNames{"A", "B"};

TEST(SurrogateChoice, AQuadraticResponseGoesToTheQuadratic) {
  const Eigen::MatrixXd X = grid();
  const SurrogateChoice c = choose_surrogate(X, eval(X, quadratic), kNames, {});
  ASSERT_TRUE(c.quadratic && c.gp);
  EXPECT_EQ(c.kind, SurrogateKind::quadratic);
  // Exact data: the leave-one-out error is rounding (1e-12 of the response's range of about 10).
  EXPECT_LT(c.quadratic_loo_rmse, 1e-10);
  Eigen::VectorXd u(2);
  u << 0.3, -0.7;
  EXPECT_NEAR(c(u), quadratic(0.3, -0.7), 1e-10);
}

TEST(SurrogateChoice, AResponseNoQuadraticFollowsGoesToTheGp) {
  const Eigen::MatrixXd X = grid();
  const SurrogateChoice c = choose_surrogate(X, eval(X, wavy), kNames, {});
  ASSERT_TRUE(c.quadratic && c.gp);
  EXPECT_EQ(c.kind, SurrogateKind::gp);
  EXPECT_LT(c.gp_loo_rmse, c.quadratic_loo_rmse);
}

TEST(SurrogateChoice, TheCallersChoiceIsKept) {
  const Eigen::MatrixXd X = grid();
  SurrogateChoiceOptions gp_only;
  gp_only.model = "gp";
  const SurrogateChoice g = choose_surrogate(X, eval(X, quadratic), kNames, gp_only);
  EXPECT_EQ(g.kind, SurrogateKind::gp);
  EXPECT_FALSE(g.quadratic_tried);
  SurrogateChoiceOptions quad_only;
  quad_only.model = "quadratic";
  const SurrogateChoice q = choose_surrogate(X, eval(X, wavy), kNames, quad_only);
  EXPECT_EQ(q.kind, SurrogateKind::quadratic);
  EXPECT_FALSE(q.gp_tried);
  SurrogateChoiceOptions bad;
  bad.model = "spline";
  EXPECT_THROW(choose_surrogate(X, eval(X, wavy), kNames, bad), DoeError);
}

// Six terms need seven points: with five only the GP is fitted.
TEST(SurrogateChoice, TooFewPointsForTheQuadratic) {
  Eigen::MatrixXd X(5, 2);
  X << -1, -1, 1, -1, 0, 0, -1, 1, 1, 0.5;
  const SurrogateChoice c = choose_surrogate(X, eval(X, wavy), kNames, {});
  EXPECT_EQ(c.kind, SurrogateKind::gp);
  EXPECT_FALSE(c.quadratic);
  EXPECT_FALSE(c.quadratic_tried);
  EXPECT_NE(c.quadratic_error.find("5 points for 6 terms"), std::string::npos);
  EXPECT_THROW(choose_surrogate(X.topRows(2), eval(X.topRows(2), wavy), kNames, {}), DoeError);
}

// The GP's noise may not fall below the floor (here a third of the responses' variance), whatever
// the likelihood prefers.
TEST(SurrogateChoice, TheNoiseFloorHolds) {
  const Eigen::MatrixXd X = grid();
  const Eigen::VectorXd y = eval(X, wavy);
  const double var = (y.array() - y.mean()).square().sum() / static_cast<double>(y.size() - 1);
  SurrogateChoiceOptions o;
  o.model = "gp";
  o.noise_variance_floor = var / 3.0;
  const SurrogateChoice c = choose_surrogate(X, y, kNames, o);
  ASSERT_TRUE(c.gp);
  // The floor is imposed as a fraction of the GP's own variance scale: to rounding of that scale.
  EXPECT_GE(c.gp->hyperparameters().noise_variance, o.noise_variance_floor * (1.0 - 1e-9));
}

}  // namespace
}  // namespace seedcal::doe
