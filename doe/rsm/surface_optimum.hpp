#pragma once
// Analysis and optimisation of a fitted response surface.
//   Stationary point of y = b0 + x'b + x'Bx (B symmetric, B_ii = b_ii, B_ij = b_ij / 2):
//   x_s = -B^-1 b / 2, y_s = b0 + x_s'b / 2; canonical form y = y_s + sum lambda_i w_i^2 with
//   lambda the eigenvalues of B (Montgomery, DAE 8th ed., sec. 11.3.1, eqs. 11.9-11.11).
//   Optimisation within bounds and "find x with y(x) = target" use NLopt (Johnson, The NLopt
//   nonlinear-optimization package) from several starts; they accept any surface y(x), a fitted
//   polynomial or a Gaussian-process mean.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "doe/regression/model_terms.hpp"

namespace seedcal::doe {

using Surface = std::function<double(const Eigen::VectorXd&)>;

struct QuadraticSurface {
  double b0 = 0.0;
  Eigen::VectorXd b;   // linear coefficients
  Eigen::MatrixXd B;   // symmetric second-order matrix
  double operator()(const Eigen::VectorXd& x) const { return b0 + x.dot(b) + x.dot(B * x); }
};

// From a fitted model's terms and coefficients (terms of order <= 2 only; missing ones are 0).
QuadraticSurface quadratic_surface(const std::vector<Term>& terms, const Eigen::VectorXd& coefficients);

struct CanonicalAnalysis {
  Eigen::VectorXd stationary_point;
  double stationary_response = 0.0;
  Eigen::VectorXd eigenvalues;    // ascending
  Eigen::MatrixXd eigenvectors;   // columns
  std::string nature;             // "maximum", "minimum", "saddle point", or "ridge" (some |lambda| ~ 0)
};
// Throws DoeError when B is singular (a ridge with no unique stationary point).
CanonicalAnalysis canonical_analysis(const QuadraticSurface& s);

struct SurfaceOptimizeOptions {
  Eigen::VectorXd lower, upper;  // the box searched (same size as x)
  bool maximize = true;
  int starts = 8;                // multi-start: the centre, then a seeded Latin hypercube
  std::uint64_t seed = 1;
  double x_tolerance = 1e-8;     // relative, on x
  int max_evaluations = 2000;    // per start
  bool IsValid(std::string* error) const;
};

struct SurfaceOptimum {
  Eigen::VectorXd x;
  double y = 0.0;
};

SurfaceOptimum optimize_surface(const Surface& f, const SurfaceOptimizeOptions& options);

struct TargetOptions {
  SurfaceOptimizeOptions search;  // bounds, starts, seed (`maximize` unused)
  double target = 0.0;
  double tolerance = 1e-6;        // |y(x) - target| accepted as a solution
  // Among the solution set, choose the x minimising this (default: distance to the box centre).
  Surface secondary;
};

struct TargetSolution {
  std::vector<Eigen::VectorXd> solution_set;  // distinct solutions found, one per start that hit
  Eigen::VectorXd chosen;                     // the one minimising the secondary objective
  double y = 0.0;                             // surface at `chosen`
  double secondary = 0.0;
  bool found = false;                         // false: the target is not reached inside the box;
                                              // `chosen` is then the point closest to it
  bool underdetermined = false;               // more unknowns than targets: a set, not a point
};

// Two stages per start: minimise (y(x) - target)^2 (BOBYQA), then, from each hit, minimise the
// secondary objective subject to |y(x) - target| <= tolerance (COBYLA).
TargetSolution solve_for_target(const Surface& f, const TargetOptions& options);

}  // namespace seedcal::doe
