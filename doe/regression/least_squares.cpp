#include "doe/regression/least_squares.hpp"

#include <cmath>
#include <limits>

#include <gsl/gsl_cdf.h>

#include "doe/core/errors.hpp"
#include "doe/core/numbers.hpp"

namespace seedcal::doe {

namespace {
// A column whose component orthogonal to the earlier columns is below this fraction of its own
// norm is taken as aliased: 1e-10 is ~1e6 times double rounding (2.2e-16) times a generous
// growth factor, and far below the smallest genuine ratio in NIST's Longley data (~1e-7).
constexpr double kAliasTolerance = 1e-10;
}  // namespace

double t_test_p(double t, int df) {
  if (df <= 0 || !std::isfinite(t)) return kNaN;
  return 2.0 * gsl_cdf_tdist_Q(std::fabs(t), static_cast<double>(df));
}

double f_test_p(double f, int df1, int df2) {
  if (df1 <= 0 || df2 <= 0 || !std::isfinite(f)) return kNaN;
  return gsl_cdf_fdist_Q(f, static_cast<double>(df1), static_cast<double>(df2));
}

LeastSquaresFit fit_least_squares(const Eigen::MatrixXd& X, const Eigen::VectorXd& y, std::vector<std::string> names) {
  const Eigen::Index n = X.rows(), p = X.cols();
  if (static_cast<Eigen::Index>(names.size()) != p) throw DoeError("fit_least_squares: names and columns differ");
  if (y.size() != n) throw DoeError("fit_least_squares: y has " + std::to_string(y.size()) + " rows, X " + std::to_string(n));
  if (n < p)
    throw DoeError("observations = " + std::to_string(n) + ": the model has " + std::to_string(p) +
                   " terms and needs at least as many runs");
  for (Eigen::Index i = 0; i < n; ++i)
    if (!std::isfinite(y(i)) || !X.row(i).allFinite())
      throw DoeError("row " + std::to_string(i + 1) + ": not a finite number");
  // Unpivoted Householder QR keeps the columns in model order, so (Q'y)_j is column j's sequential
  // contribution (Seber & Lee, Linear Regression Analysis, 2nd ed., sec. 11.3).
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(X);
  const Eigen::MatrixXd R = qr.matrixQR().topRows(p).triangularView<Eigen::Upper>();
  for (Eigen::Index j = 0; j < p; ++j) {
    const double cn = X.col(j).norm();
    if (std::fabs(R(j, j)) <= kAliasTolerance * std::max(cn, std::numeric_limits<double>::min()))
      throw DoeError("term " + names[static_cast<std::size_t>(j)] +
                     ": aliased with (a linear combination of) the terms before it; the design cannot "
                     "estimate it (drop the term or add runs)");
  }
  LeastSquaresFit f;
  f.names = std::move(names);
  f.n = static_cast<int>(n);
  f.parameters = static_cast<int>(p);
  f.df_residual = static_cast<int>(n - p);
  const Eigen::VectorXd qty = qr.householderQ().adjoint() * y;
  f.sequential_ss = qty.head(p).array().square().matrix();
  f.coefficients = R.triangularView<Eigen::Upper>().solve(qty.head(p));
  f.fitted = X * f.coefficients;
  f.residuals = y - f.fitted;
  // One step of iterative refinement on the residual (Golub & Van Loan sec. 5.3.8): recovers the
  // digits an ill-conditioned model matrix (NIST Longley) costs the first solve.
  const Eigen::VectorXd dq = qr.householderQ().adjoint() * f.residuals;
  f.coefficients += R.triangularView<Eigen::Upper>().solve(dq.head(p));
  f.fitted = X * f.coefficients;
  f.residuals = y - f.fitted;
  f.sse = f.residuals.squaredNorm();
  f.mse = f.df_residual > 0 ? f.sse / f.df_residual : kNaN;
  f.sigma = std::sqrt(f.mse);
  const Eigen::MatrixXd Rinv = R.triangularView<Eigen::Upper>().solve(Eigen::MatrixXd::Identity(p, p));
  f.unscaled_covariance = Rinv * Rinv.transpose();
  f.standard_errors = (f.unscaled_covariance.diagonal() * f.mse).array().sqrt().matrix();
  f.t = f.coefficients.cwiseQuotient(f.standard_errors);
  f.p.resize(p);
  for (Eigen::Index j = 0; j < p; ++j) f.p(j) = t_test_p(f.t(j), f.df_residual);
  const Eigen::MatrixXd Q1 = qr.householderQ() * Eigen::MatrixXd::Identity(n, p);
  f.leverage = Q1.rowwise().squaredNorm();
  f.press = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    // h_ii = 1 (a run the model must pass through): its deleted residual is undefined.
    if (1.0 - f.leverage(i) < 1e-10) {
      f.press = kNaN;
      break;
    }
    f.press += std::pow(f.residuals(i) / (1.0 - f.leverage(i)), 2);
  }
  return f;
}

}  // namespace seedcal::doe
