#include "doe/core/random.hpp"
#include "doe/surrogate/posterior.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <random>

#include "doe/core/errors.hpp"

namespace seedcal::doe {
namespace {

// Log-likelihood of every target at x.
double log_likelihood(const std::vector<TargetEvidence>& targets, const Eigen::VectorXd& x) {
  double sum = 0.0;
  for (const TargetEvidence& t : targets) {
    const GpPrediction p = t.response(x);
    const double var = std::max(p.variance, 0.0) + t.value_variance;
    const double r = t.value - p.mean;
    // A target with no uncertainty at all (a deterministic surrogate, an exact measurement): a
    // vanishing variance would make the density a delta; the floor keeps it a narrow ridge.
    const double v = std::max(var, 1e-24 * (1.0 + t.value * t.value));
    sum += -0.5 * r * r / v - 0.5 * std::log(v);
  }
  return sum;
}

// The value below which `q` of the weight lies, along coordinate `d`.
double weighted_quantile(const Eigen::MatrixXd& pts, const Eigen::VectorXd& w, std::vector<Eigen::Index>& order,
                         int d, double q) {
  std::sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) { return pts(a, d) < pts(b, d); });
  double cum = 0.0;
  for (Eigen::Index i : order) {
    cum += w(i);
    if (cum >= q) return pts(i, d);
  }
  return pts(order.back(), d);
}

}  // namespace

Posterior posterior(const std::vector<TargetEvidence>& targets, const PosteriorOptions& o) {
  const Eigen::Index k = o.lower.size();
  if (k == 0 || o.upper.size() != k) throw DoeError("posterior: the box needs lower and upper bounds of one size");
  for (Eigen::Index d = 0; d < k; ++d)
    if (!(o.lower(d) < o.upper(d))) throw DoeError("posterior: every lower bound must lie below its upper bound");
  if (targets.empty()) throw DoeError("posterior: no target");
  if (!(o.level > 0.0 && o.level < 1.0)) throw DoeError("posterior: the level must lie in (0, 1)");

  // The points: a regular grid over one or two parameters (cell centres of equal volume), uniform
  // random points over more.
  Eigen::MatrixXd pts;
  if (k <= 2) {
    const int n = std::max(3, o.grid_points);
    const Eigen::Index total = k == 1 ? n : static_cast<Eigen::Index>(n) * n;
    pts.resize(total, k);
    for (Eigen::Index i = 0; i < total; ++i)
      for (Eigen::Index d = 0; d < k; ++d) {
        const Eigen::Index idx = d == 0 ? i % n : i / n;
        pts(i, d) = o.lower(d) + (static_cast<double>(idx) + 0.5) / n * (o.upper(d) - o.lower(d));
      }
  } else {
    std::mt19937_64 rng(o.seed);
        pts.resize(std::max(1000, o.samples), k);
    for (Eigen::Index i = 0; i < pts.rows(); ++i)
      for (Eigen::Index d = 0; d < k; ++d) pts(i, d) = o.lower(d) + unit_uniform(rng) * (o.upper(d) - o.lower(d));
  }

  Eigen::VectorXd logp(pts.rows());
  for (Eigen::Index i = 0; i < pts.rows(); ++i) logp(i) = log_likelihood(targets, pts.row(i).transpose());
  Posterior out;
  Eigen::Index best = 0;
  const double top = logp.maxCoeff(&best);
  out.weights = (logp.array() - top).exp().matrix();
  out.weights /= out.weights.sum();
  out.mode = pts.row(best).transpose();

  std::vector<Eigen::Index> order(static_cast<std::size_t>(pts.rows()));
  std::iota(order.begin(), order.end(), Eigen::Index{0});
  const double tail = 0.5 * (1.0 - o.level);
  out.interval_lo.resize(k);
  out.interval_hi.resize(k);
  out.median.resize(k);
  for (Eigen::Index d = 0; d < k; ++d) {
    out.interval_lo(d) = weighted_quantile(pts, out.weights, order, static_cast<int>(d), tail);
    out.median(d) = weighted_quantile(pts, out.weights, order, static_cast<int>(d), 0.5);
    out.interval_hi(d) = weighted_quantile(pts, out.weights, order, static_cast<int>(d), 1.0 - tail);
  }
  // The highest-density region: the heaviest points until `level` of the mass.
  std::sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) { return out.weights(a) > out.weights(b); });
  double cum = 0.0;
  for (Eigen::Index i : order) {
    cum += out.weights(i);
    out.hpd_threshold = out.weights(i);
    out.hpd_log_likelihood = logp(i);
    if (cum >= o.level) break;
  }
  out.points = std::move(pts);
  return out;
}

bool in_credible_region(const std::vector<TargetEvidence>& targets, const Posterior& p, const Eigen::VectorXd& x) {
  // Points of equal likelihood are all in or all out: rounding in the sum must not split them.
  const double b = p.hpd_log_likelihood;
  return log_likelihood(targets, x) >= b - 1e-12 * (1.0 + std::abs(b));
}

double pooled_replicate_variance(const Eigen::MatrixXd& X, const Eigen::VectorXd& y, int* df) {
  std::map<std::vector<double>, std::vector<double>> groups;
  for (Eigen::Index i = 0; i < X.rows(); ++i) {
    std::vector<double> key(static_cast<std::size_t>(X.cols()));
    for (Eigen::Index j = 0; j < X.cols(); ++j) key[static_cast<std::size_t>(j)] = X(i, j);
    groups[key].push_back(y(i));
  }
  double ss = 0.0;
  int dof = 0;
  for (const auto& [key, v] : groups) {
    if (v.size() < 2) continue;
    const double mean = std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
    for (double x : v) ss += (x - mean) * (x - mean);
    dof += static_cast<int>(v.size()) - 1;
  }
  if (df) *df = dof;
  return dof > 0 ? ss / dof : 0.0;
}

}  // namespace seedcal::doe
