#pragma once
// Regression analysis of a designed experiment: least-squares fit of a polynomial model and its
// analysis-of-variance table, as statistics packages print it (Montgomery, DAE 8th ed., sec. 10.3
// and 11.3; Myers, Montgomery & Anderson-Cook, RSM 3rd ed., ch. 2):
//   model        df p-1,  SS = sum of the term rows
//   one row per term: sequential (type I) SS, each term adjusted for the terms before it
//   residual     df n-p,  SS_E = sum e_i^2
//   lack of fit  df m-p,  SS_E - SS_PE        (m distinct factor settings; when replicates exist
//   pure error   df n-m,  sum over settings of sum (y - ybar_setting)^2        and m > p)
//   total        df n-1,  sum (y - ybar)^2
// F = MS / MS_residual for the model and the terms, MS_LOF / MS_PE for lack of fit, p from the F
// distribution. R2 = SS_model / SS_total; adjusted R2 = 1 - MS_E / (SS_total/(n-1)); predicted R2 =
// 1 - PRESS / SS_total; adequate precision = (max yhat - min yhat) / sqrt(p MS_E / n), the mean
// prediction variance over the runs being p sigma^2 / n since sum h_ii = p (Design-Expert's
// "Adeq Precision", as printed in Montgomery's DAE examples).
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "doe/regression/least_squares.hpp"
#include "doe/regression/model_terms.hpp"

namespace seedcal::doe {

struct AnovaRow {
  std::string source;
  int df = 0;
  double ss = 0.0;
  double ms = 0.0;
  double f = 0.0;   // NaN when there is no test
  double p = 0.0;   // NaN when there is no test
};

struct RegressionAnalysis {
  std::vector<Term> terms;
  LeastSquaresFit fit;
  std::vector<AnovaRow> anova;       // model, the terms, residual, [lack of fit, pure error], total
  Eigen::VectorXd adjusted_ss;       // per term (intercept: NaN): partial (type III) SS, b_j^2 / [(X'X)^-1]_jj
  double r2 = 0.0, adj_r2 = 0.0, pred_r2 = 0.0, press = 0.0;
  double adequate_precision = 0.0;
  double mean = 0.0;                 // response mean
  int distinct_points = 0;           // distinct factor settings

  const AnovaRow& row(const std::string& source) const;  // throws DoeError when absent
  bool has_row(const std::string& source) const;
  double coefficient(const std::string& term) const;
};

// X: runs x factors (one column per factor named in the terms' powers), y: the response.
// The first term must be the intercept. Throws DoeError on aliased terms or too few runs.
RegressionAnalysis analyze_regression(const Eigen::MatrixXd& X, const Eigen::VectorXd& y, const std::vector<Term>& terms);

// Human-readable table: coefficients with se, t, p; the ANOVA table; R2, adjusted, predicted R2.
std::string format_regression(const RegressionAnalysis& a);

}  // namespace seedcal::doe
