#pragma once
// Main effects of two-level factors and their significance (Montgomery, DAE 8th ed., sec. 6.2 and
// 8.7.2): effect = ybar(high) - ybar(low). Its standard error comes from
//   - dummy columns (Plackett & Burman 1946; Montgomery sec. 8.7): each unassigned column's
//     "effect" estimates only noise, so s_eff^2 = sum(dummy effect^2) / m with m degrees of
//     freedom; or
//   - the residual of the main-effects (first-order) model: Var(effect) = s^2 (1/n_high + 1/n_low),
//     with the residual's degrees of freedom.
// t = effect / s_eff, p two-sided from Student t. The Pareto ranking sorts by |effect|.
#include <string>
#include <vector>

#include <Eigen/Dense>

namespace seedcal::doe {

struct Effect {
  std::string name;
  double low = 0.0, high = 0.0;  // the factor's two levels
  double effect = 0.0;           // ybar(high) - ybar(low)
  double se = 0.0, t = 0.0, p = 0.0;  // NaN when no error estimate exists
  int pareto_rank = 0;           // 1 = largest |effect|
};

struct EffectsAnalysis {
  std::vector<Effect> effects;   // in input order
  std::vector<int> pareto;       // indices into effects, largest |effect| first
  int df_error = 0;
  std::string error_source;      // "dummy columns", "residual" or "none"
};

// True when the column takes exactly two distinct values.
bool is_two_level(const Eigen::VectorXd& column);

// X: runs x factors, every column two-level (throws DoeError naming a column that is not);
// dummies: runs x m dummy columns (may have 0 columns): when m > 0 they give the error.
EffectsAnalysis main_effects(const Eigen::MatrixXd& X, const Eigen::VectorXd& y, const std::vector<std::string>& names,
                             const Eigen::MatrixXd& dummies = Eigen::MatrixXd());

}  // namespace seedcal::doe
