// The calibration posterior (doe/surrogate/posterior.hpp): exact intervals on a known likelihood,
// the pooled replicate noise, and twin studies: synthetic responses with a known truth and known
// noise, sampled on the calibration's design, fitted by a Gaussian process with the noise fixed from
// the replicates, and inverted through the same posterior code a calibration uses. A 95 % interval
// must cover the truth in at least 90 % of 200 seeded trials (the nominal 95 % less the Monte Carlo
// scatter of 200 Bernoulli trials, sqrt(0.95 0.05 / 200) = 1.5 %, three times over, and the GP's
// approximation of the response).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "doe/core/errors.hpp"
#include "doe/designs/central_composite.hpp"
#include "doe/surrogate/posterior.hpp"

namespace seedcal::doe {
namespace {

// mu(x) = 10 x exactly (no surrogate variance), T = 5 with variance 1: the posterior of x is
// N(0.5, 0.1^2) truncated to [-1, 1], on a grid of cells 1e-4 wide.
TargetEvidence linear_target() {
  TargetEvidence t;
  t.response = [](const Eigen::VectorXd& x) { return GpPrediction{10.0 * x(0), 0.0}; };
  t.value = 5.0;
  t.value_variance = 1.0;
  return t;
}

Posterior linear_posterior(const TargetEvidence& t) {
  PosteriorOptions o;
  o.lower = Eigen::VectorXd::Constant(1, -1.0);
  o.upper = Eigen::VectorXd::Constant(1, 1.0);
  o.grid_points = 20001;
  return posterior({t}, o);
}

TEST(Posterior, LinearResponseGivesTheAnalyticInterval) {
  // The 95 % interval of N(0.5, 0.1^2) is 0.5 +- 1.95996 x 0.1.
  const Posterior p = linear_posterior(linear_target());
  // Grid cells of 1e-4: the quantiles land within one cell.
  EXPECT_NEAR(p.interval_lo(0), 0.5 - 0.195996, 2e-4);
  EXPECT_NEAR(p.interval_hi(0), 0.5 + 0.195996, 2e-4);
  EXPECT_NEAR(p.median(0), 0.5, 2e-4);
  EXPECT_NEAR(p.mode(0), 0.5, 2e-4);
}

TEST(Posterior, FlatResponseLeavesTheWholeBoxAndEveryPointInItsRegion) {
  // A response that does not depend on the parameter: the posterior is the uniform prior.
  TargetEvidence t;
  t.response = [](const Eigen::VectorXd&) { return GpPrediction{100.0, 4.0}; };
  t.value = 101.0;
  PosteriorOptions o;
  o.lower = Eigen::VectorXd::Constant(1, 0.3);
  o.upper = Eigen::VectorXd::Constant(1, 0.9);
  const Posterior p = posterior({t}, o);
  // 2.5 % and 97.5 % of the box, to a grid cell (0.6 / 201).
  EXPECT_NEAR(p.interval_lo(0), 0.3 + 0.025 * 0.6, 0.6 / 201);
  EXPECT_NEAR(p.interval_hi(0), 0.3 + 0.975 * 0.6, 0.6 / 201);
  // Every point of the box is in the credible region: the ends lie outside the marginal's central
  // 95 % interval, yet the data favour them as much as the middle.
  for (double x : {0.3, 0.6, 0.897, 0.9}) EXPECT_TRUE(in_credible_region({t}, p, Eigen::VectorXd::Constant(1, x))) << x;
}

TEST(Posterior, TheCredibleRegionOfAPeakIsItsHighestDensityInterval) {
  // N(0.5, 0.1^2) on [-1, 1], whose highest-density 95 % region is 0.5 +- 1.95996 x 0.1.
  const TargetEvidence t = linear_target();
  const Posterior p = linear_posterior(t);
  const auto in = [&](double x) { return in_credible_region({t}, p, Eigen::VectorXd::Constant(1, x)); };
  EXPECT_TRUE(in(0.5));
  EXPECT_TRUE(in(0.5 + 0.19));
  EXPECT_TRUE(in(0.5 - 0.19));
  EXPECT_FALSE(in(0.5 + 0.20));
  EXPECT_FALSE(in(0.5 - 0.20));
  EXPECT_FALSE(in(-1.0));
}

TEST(Posterior, PooledReplicateVariance) {
  Eigen::MatrixXd X(6, 2);
  X << 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2;
  Eigen::VectorXd y(6);
  y << 1, 2, 3, 10, 14, 99;
  int df = 0;
  // Groups (1, 2, 3): ss 2, df 2; (10, 14): ss 8, df 1; (99) alone: nothing.
  EXPECT_DOUBLE_EQ(pooled_replicate_variance(X, y, &df), 10.0 / 3.0);
  EXPECT_EQ(df, 3);
}

TEST(Posterior, RefusesBadInput) {
  TargetEvidence t;
  t.response = [](const Eigen::VectorXd&) { return GpPrediction{0.0, 1.0}; };
  PosteriorOptions o;
  EXPECT_THROW(posterior({t}, o), DoeError);
  o.lower = Eigen::VectorXd::Constant(1, 1.0);
  o.upper = Eigen::VectorXd::Constant(1, 0.0);
  EXPECT_THROW(posterior({t}, o), DoeError);
  o.upper(0) = 2.0;
  EXPECT_THROW(posterior({}, o), DoeError);
}

// A twin calibration on the box [-1, 1]^2: a face-centred CCD with every point run twice and three
// centre runs, responses f_t(u) + N(0, sd^2), a GP per target with the noise fixed at the pooled
// replicate variance, targets measured as f_t(u*) + N(0, lab_sd^2 / lab_repeats).
struct Twin {
  int covered[2] = {0, 0};
  double width[2] = {0.0, 0.0};  // mean interval width
};

// One synthetic target: its mean response, its run-to-run sd, and the laboratory's sd (five repeats).
struct Synthetic {
  std::function<double(const Eigen::VectorXd&)> f;
  double sd, lab_sd;
};

Twin twin_study(const std::vector<Synthetic>& targets_in, int trials) {
  CentralCompositeOptions c;
  c.factors = 2;
  c.type = CcdType::face_centered;
  c.center_points = 3;
  const Eigen::MatrixXd design = central_composite(c).coded;
  Eigen::MatrixXd X(2 * design.rows(), 2);
  X << design, design;
  Twin out;
  std::mt19937_64 rng(7);
  std::normal_distribution<double> z(0.0, 1.0);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < trials; ++trial) {
    const Eigen::Vector2d truth(u(rng), u(rng));
    std::vector<TargetEvidence> targets;
    std::vector<std::shared_ptr<GaussianProcess>> gps;
    for (const Synthetic& syn : targets_in) {
      const auto& ft = syn.f;
      Eigen::VectorXd y(X.rows());
      for (Eigen::Index i = 0; i < X.rows(); ++i) y(i) = ft(X.row(i).transpose()) + syn.sd * z(rng);
      int df = 0;
      GpOptions o;
      o.fit_noise = false;
      o.noise_variance = pooled_replicate_variance(X, y, &df);
      o.seed = static_cast<std::uint64_t>(trial) + 1;
      o.starts = 3;
      auto gp = std::make_shared<GaussianProcess>(GaussianProcess::fit(X, y, o));
      gps.push_back(gp);
      TargetEvidence t;
      t.response = [gp](const Eigen::VectorXd& x) { return gp->predict(x); };
      t.value_variance = syn.lab_sd * syn.lab_sd / 5.0;
      t.value = ft(truth) + std::sqrt(t.value_variance) * z(rng);
      targets.push_back(t);
    }
    PosteriorOptions po;
    po.lower = Eigen::VectorXd::Constant(2, -1.0);
    po.upper = Eigen::VectorXd::Constant(2, 1.0);
    po.grid_points = 81;
    const Posterior p = posterior(targets, po);
    for (int d = 0; d < 2; ++d) {
      // Half a grid cell of slack: the interval's ends are cell centres.
      const double cell = 2.0 / 81;
      out.covered[d] += truth(d) >= p.interval_lo(d) - 0.5 * cell && truth(d) <= p.interval_hi(d) + 0.5 * cell;
      out.width[d] += (p.interval_hi(d) - p.interval_lo(d)) / trials;
    }
  }
  return out;
}

TEST(Posterior, TwinStudiesCoverTheTruth) {
  constexpr int kTrials = 200;
  // Two targets, two parameters, each answering mostly one of them, with a curvature and an
  // interaction the GP must learn: a shear-box-like target (strength about 100, run-to-run sd 8,
  // laboratory sd 5) that follows the first parameter, and a heap-like one (angle about 30, run sd
  // 1.5, laboratory sd 1.16: the paper's piling) that follows the second.
  const auto f1 = [](const Eigen::VectorXd& x) { return 100.0 + 15.0 * x(0) + 4.0 * x(1) + 3.0 * x(0) * x(1) - 4.0 * x(0) * x(0); };
  const auto f2 = [](const Eigen::VectorXd& x) { return 30.0 + 1.5 * x(0) + 8.0 * x(1) + 1.0 * x(1) * x(1); };
  const Twin both = twin_study({{f1, 8.0, 5.0}, {f2, 1.5, 1.16}}, kTrials);
  std::printf("two targets: coverage %d / %d and %d / %d, mean widths %.3f and %.3f (of 2)\n", both.covered[0],
              kTrials, both.covered[1], kTrials, both.width[0], both.width[1]);
  EXPECT_GE(both.covered[0], 0.90 * kTrials);
  EXPECT_GE(both.covered[1], 0.90 * kTrials);
  // The heap-like target pins its parameter: its interval is within a third of the box, a
  // calibration's criterion for "identified" (posterior sd about sqrt(1.16^2 / 5 + 1.5^2 / 5) / 8,
  // 0.11, so a width near 0.45).
  EXPECT_LT(both.width[1], 2.0 / 3.0);

  // One target, two parameters: a curve of solutions; the intervals must still cover the truth.
  const Twin one = twin_study({{f1, 8.0, 5.0}}, kTrials);
  std::printf("one target: coverage %d / %d and %d / %d, mean widths %.3f and %.3f (of 2)\n", one.covered[0],
              kTrials, one.covered[1], kTrials, one.width[0], one.width[1]);
  EXPECT_GE(one.covered[0], 0.90 * kTrials);
  EXPECT_GE(one.covered[1], 0.90 * kTrials);
}

}  // namespace
}  // namespace seedcal::doe
