#pragma once
// Acquisition rules that choose where to evaluate an expensive function next from a Gaussian-process
// surrogate, and batch selection for parallel evaluation.
//   expected improvement (minimisation; Jones, Schonlau & Welch, J. Global Optim. 13 (1998) 455, eq. 15):
//     EI = (y* - mu) Phi(z) + s phi(z),  z = (y* - mu) / s;
//   target matching: the expected reduction of the distance to a target T below the best distance
//     d* so far, E[max(0, d* - |Y - T|)], Y ~ N(mu, s^2). With a = T - d*, b = T + d* and the
//     identity int_l^u (y - c) N(y; mu, s) dy = (mu - c)[Phi(z_u) - Phi(z_l)] - s[phi(z_u) - phi(z_l)]:
//     E = (mu - a)[Phi(z_T) - Phi(z_a)] - s[phi(z_T) - phi(z_a)]
//       + (b - mu)[Phi(z_b) - Phi(z_T)] + s[phi(z_b) - phi(z_T)]  (derived here; the same idea as
//     the expected improvement for contour estimation of Ranjan, Bingham & Michailidis,
//     Technometrics 50 (2008) 527);
//   maximum variance: the point where the surrogate is least sure (global accuracy; active
//     learning, MacKay, Neural Computation 4 (1992) 590).
// Batches: "kriging believer" (Ginsbourger, Le Riche & Carraro 2010): take the best point, add the
// surrogate's own mean there as if observed (hyperparameters held), and choose again.
#include <cstdint>
#include <string>

#include <Eigen/Dense>

#include "doe/surrogate/gaussian_process.hpp"

namespace seedcal::doe {

enum class AcquisitionRule { expected_improvement, target, max_variance };
const char* to_string(AcquisitionRule r);
AcquisitionRule parse_acquisition_rule(const std::string& s);  // "ei", "target", "variance"

double expected_improvement(double mean, double sd, double best, bool minimize = true);
double target_improvement(double mean, double sd, double target, double best_distance);

struct AcquisitionOptions {
  AcquisitionRule rule = AcquisitionRule::expected_improvement;
  bool minimize = true;            // expected improvement: minimise (true) or maximise
  double target = 0.0;             // target rule
  Eigen::VectorXd lower, upper;    // the box searched
  int candidates = 1000;           // random candidates, then a local polish of the best (BOBYQA)
  std::uint64_t seed = 1;
  bool IsValid(std::string* error) const;
};

// Acquisition value at x (larger is better) for the given incumbent (best value for EI, best
// distance for target; unused for max_variance).
double acquisition_value(const GaussianProcess& gp, const Eigen::VectorXd& x, const AcquisitionOptions& o,
                         double incumbent);

// Incumbent from the surrogate's mean at the observed points (robust to noise: Picheny, Wagner &
// Ginsbourger, Struct. Multidisc. Optim. 48 (2013) 607, "plug-in" criteria).
double incumbent(const GaussianProcess& gp, const AcquisitionOptions& o);

// The next `batch` points, one per row.
Eigen::MatrixXd select_batch(const GaussianProcess& gp, const AcquisitionOptions& o, int batch = 1);

}  // namespace seedcal::doe
