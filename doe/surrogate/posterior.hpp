#pragma once
// The posterior of the parameters of an expensive, noisy simulation given measured targets: a
// uniform prior over a box, and for each target a Gaussian likelihood of the measured value around
// the simulation's mean response,
//
//   p(theta | T) ∝ prod_t N(T_t ; mu_t(theta), s_t^2(theta) + v_t),   theta in the box,
//
// where mu_t and s_t^2 are a surrogate's prediction of the mean response and the variance of that
// prediction (for a Gaussian process fitted with the run-to-run noise fixed from replicates: the
// latent variance, R&W eq. 2.26, so the noise of single runs is not mistaken for shape), and v_t is
// the variance of the measured mean (sd^2 / repeats; 0 when the measurement gives no sd). This is
// the Kennedy & O'Hagan (2001, J. R. Stat. Soc. B 63, 425) calibration without the model-
// discrepancy term, with the emulator's uncertainty carried into the likelihood (their sec. 4.2).
//
// The density is evaluated on a regular grid (one or two parameters) or at uniform random points
// (three or more) over the box; the marginal of each parameter gives its equal-tailed credible
// interval. A parameter on which the targets depend weakly keeps a wide interval, whatever point an
// optimiser picked: that is what `identified` reports in a calibration.
#include <cstdint>
#include <functional>
#include <vector>

#include <Eigen/Dense>

#include "doe/surrogate/gaussian_process.hpp"

namespace seedcal::doe {

// One target's evidence.
struct TargetEvidence {
  // The surrogate of the simulation's mean response at theta: mean and the variance of that mean.
  std::function<GpPrediction(const Eigen::VectorXd&)> response;
  double value = 0.0;           // the measured value
  double value_variance = 0.0;  // variance of the measured mean (sd^2 / repeats); 0: none known
};

struct PosteriorOptions {
  Eigen::VectorXd lower, upper;  // the box, with a uniform prior over it
  int grid_points = 201;         // per parameter, for one or two parameters
  int samples = 40000;           // uniform random points, for three or more
  double level = 0.95;           // credible level of the intervals
  std::uint64_t seed = 1;        // the random points
};

struct Posterior {
  Eigen::VectorXd interval_lo, interval_hi;  // equal-tailed marginal intervals at `level`
  Eigen::VectorXd median;                    // marginal medians
  Eigen::VectorXd mode;                      // the evaluated point of highest density
  // Where the density was evaluated and its normalised weights (sum 1), for pictures of the
  // credible region; one point per row.
  Eigen::MatrixXd points;
  Eigen::VectorXd weights;
  // Smallest total weight that holds `level` of the mass when the points are taken in decreasing
  // density: the threshold of the highest-density region (for a band around a solution curve).
  double hpd_threshold = 0.0;
  // The log-likelihood at that region's boundary (the lightest point it holds), for telling
  // whether a point off the evaluated ones lies in the region (in_credible_region).
  double hpd_log_likelihood = 0.0;
};

// Throws DoeError on an empty box, a box with lower >= upper, no targets, or a level outside (0, 1).
Posterior posterior(const std::vector<TargetEvidence>& targets, const PosteriorOptions& options);

// Whether x (inside the posterior's box) lies in its highest-density region at the level it was
// taken at: the targets' likelihood at x at least that at the region's boundary. Unlike the
// marginal intervals, this is a statement about the point as a whole: where the posterior is flat
// every point of the box is in the region, however far into a marginal's tails it lies.
bool in_credible_region(const std::vector<TargetEvidence>& targets, const Posterior& p, const Eigen::VectorXd& x);

// Run-to-run noise variance pooled over the groups of identical inputs with two or more runs:
// sum_g (n_g - 1) s_g^2 / sum_g (n_g - 1) (the replicates' pure-error mean square; Montgomery, DAE
// 8th ed., sec. 6.6). `df` receives sum_g (n_g - 1); 0 (and a variance of 0) when no input repeats.
double pooled_replicate_variance(const Eigen::MatrixXd& X, const Eigen::VectorXd& y, int* df);

}  // namespace seedcal::doe
