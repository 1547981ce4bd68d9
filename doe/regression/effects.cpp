#include "doe/regression/effects.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "doe/core/errors.hpp"
#include "doe/core/numbers.hpp"
#include "doe/regression/least_squares.hpp"

namespace seedcal::doe {

namespace {

struct Split {
  double low, high, effect;
  int n_low, n_high;
};

Split split(const Eigen::VectorXd& c, const Eigen::VectorXd& y) {
  const double lo = c.minCoeff(), hi = c.maxCoeff();
  double sl = 0.0, sh = 0.0;
  int nl = 0, nh = 0;
  for (Eigen::Index i = 0; i < c.size(); ++i) {
    if (c(i) == hi) { sh += y(i); ++nh; }
    else { sl += y(i); ++nl; }
  }
  return {lo, hi, sh / nh - sl / nl, nl, nh};
}
}  // namespace

bool is_two_level(const Eigen::VectorXd& c) {
  if (c.size() < 2) return false;
  const double lo = c.minCoeff(), hi = c.maxCoeff();
  if (!(lo < hi)) return false;
  return (c.array() == lo || c.array() == hi).all();
}

EffectsAnalysis main_effects(const Eigen::MatrixXd& X, const Eigen::VectorXd& y, const std::vector<std::string>& names,
                             const Eigen::MatrixXd& dummies) {
  if (static_cast<Eigen::Index>(names.size()) != X.cols()) throw DoeError("main_effects: names and columns differ");
  for (Eigen::Index j = 0; j < X.cols(); ++j)
    if (!is_two_level(X.col(j)))
      throw DoeError("factor " + names[static_cast<std::size_t>(j)] + ": takes more or fewer than two levels; "
                     "main effects need a two-level design");
  EffectsAnalysis a;
  double s_eff2 = kNaN;  // variance of an effect when n_low = n_high = n/2 (dummies) or per factor
  double s2 = kNaN;      // residual variance (residual route)
  if (dummies.cols() > 0) {
    double sum = 0.0;
    for (Eigen::Index j = 0; j < dummies.cols(); ++j) {
      if (!is_two_level(dummies.col(j))) throw DoeError("dummy column " + std::to_string(j + 1) + ": not two-level");
      sum += std::pow(split(dummies.col(j), y).effect, 2);
    }
    s_eff2 = sum / static_cast<double>(dummies.cols());
    a.df_error = static_cast<int>(dummies.cols());
    a.error_source = "dummy columns";
  } else {
    Eigen::MatrixXd M(X.rows(), X.cols() + 1);
    M.col(0).setOnes();
    M.rightCols(X.cols()) = X;
    std::vector<std::string> n2{"intercept"};
    n2.insert(n2.end(), names.begin(), names.end());
    const LeastSquaresFit f = fit_least_squares(M, y, n2);
    a.df_error = f.df_residual;
    a.error_source = f.df_residual > 0 ? "residual" : "none";
    s2 = f.mse;
  }
  for (Eigen::Index j = 0; j < X.cols(); ++j) {
    const Split s = split(X.col(j), y);
    Effect e;
    e.name = names[static_cast<std::size_t>(j)];
    e.low = s.low;
    e.high = s.high;
    e.effect = s.effect;
    e.se = dummies.cols() > 0 ? std::sqrt(s_eff2) : std::sqrt(s2 * (1.0 / s.n_low + 1.0 / s.n_high));
    e.t = a.df_error > 0 ? e.effect / e.se : kNaN;
    e.p = t_test_p(e.t, a.df_error);
    if (a.df_error <= 0) e.se = kNaN;
    a.effects.push_back(e);
  }
  a.pareto.resize(a.effects.size());
  std::iota(a.pareto.begin(), a.pareto.end(), 0);
  std::stable_sort(a.pareto.begin(), a.pareto.end(), [&](int l, int r) {
    return std::fabs(a.effects[static_cast<std::size_t>(l)].effect) > std::fabs(a.effects[static_cast<std::size_t>(r)].effect);
  });
  for (std::size_t r = 0; r < a.pareto.size(); ++r) a.effects[static_cast<std::size_t>(a.pareto[r])].pareto_rank = static_cast<int>(r) + 1;
  return a;
}

}  // namespace seedcal::doe
