#pragma once
// Ordinary least squares by Householder QR of the model matrix (no normal equations: Golub & Van
// Loan, Matrix Computations, 4th ed., sec. 5.3.3), with the statistics a regression table prints.
#include <string>
#include <vector>

#include <Eigen/Dense>

namespace seedcal::doe {

struct LeastSquaresFit {
  std::vector<std::string> names;      // one per column of the model matrix
  Eigen::VectorXd coefficients;        // b = R^-1 Q1' y
  Eigen::VectorXd standard_errors;     // sqrt(s^2 diag((X'X)^-1)), (X'X)^-1 = R^-1 R^-T
  Eigen::VectorXd t;                   // b / se
  Eigen::VectorXd p;                   // two-sided, Student t with df_residual (NaN when df = 0)
  Eigen::MatrixXd unscaled_covariance; // (X'X)^-1
  Eigen::VectorXd fitted, residuals;
  Eigen::VectorXd leverage;            // h_ii = ||row i of Q1||^2, the hat matrix diagonal
  Eigen::VectorXd sequential_ss;       // (Q'y)_j^2: the type I sum of squares of column j given
                                       // the columns before it (the "effects" of R's lm)
  int n = 0;                           // observations
  int parameters = 0;                  // columns
  int df_residual = 0;                 // n - parameters
  double sse = 0.0;                    // residual sum of squares, sum e_i^2
  double mse = 0.0;                    // sse / df_residual (NaN when df = 0)
  double sigma = 0.0;                  // sqrt(mse)
  double press = 0.0;                  // sum (e_i / (1 - h_ii))^2 (Allen 1974); NaN if some h_ii = 1
};

// Throws DoeError when n < columns or a column is a linear combination of the columns before it
// (an aliased term), naming that column.
LeastSquaresFit fit_least_squares(const Eigen::MatrixXd& X, const Eigen::VectorXd& y,
                                  std::vector<std::string> names);

// Two-sided p-value of a Student t statistic (GSL: 2 Q_t(|t|; df)); NaN when df <= 0.
double t_test_p(double t, int df);
// Upper tail of the F distribution (GSL gsl_cdf_fdist_Q); NaN when df2 <= 0.
double f_test_p(double f, int df1, int df2);

}  // namespace seedcal::doe
