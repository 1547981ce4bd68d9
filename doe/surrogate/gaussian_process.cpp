#include "doe/core/random.hpp"
#include "doe/surrogate/gaussian_process.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>

#include <nlopt.hpp>

#include "doe/core/errors.hpp"

namespace seedcal::doe {

const char* to_string(KernelKind k) { return k == KernelKind::matern52 ? "matern52" : "squared_exponential"; }
const char* to_string(MeanKind m) { return m == MeanKind::linear ? "linear" : "constant"; }

double GpPrediction::sd() const { return std::sqrt(std::max(variance, 0.0)); }

bool GpOptions::IsValid(std::string* error) const {
  Problems p;
  p.require(starts >= 1, "GpOptions.starts", starts, "must be >= 1");
  p.require(max_evaluations >= 20, "GpOptions.max_evaluations", max_evaluations, "must be >= 20");
  p.require(min_length > 0.0, "GpOptions.min_length", min_length, "must be > 0");
  p.require(max_length > min_length, "GpOptions.max_length", max_length, "must exceed min_length");
  p.require(min_noise > 0.0 && min_noise < 1.0, "GpOptions.min_noise", min_noise, "must be in (0, 1)");
  p.require(noise_variance >= 0.0, "GpOptions.noise_variance", noise_variance, "must be >= 0");
  return p.report(error);
}

double kernel_value(KernelKind kind, const Eigen::VectorXd& a, const Eigen::VectorXd& b, const Eigen::VectorXd& l,
                    double sf2) {
  const double r2 = (a - b).cwiseQuotient(l).squaredNorm();
  if (kind == KernelKind::squared_exponential) return sf2 * std::exp(-0.5 * r2);  // R&W eq. 4.9
  const double s5r = std::sqrt(5.0 * r2);
  return sf2 * (1.0 + s5r + 5.0 * r2 / 3.0) * std::exp(-s5r);  // R&W eq. 4.17, nu = 5/2
}

namespace {

constexpr double kLog2Pi = 1.8378770664093453;  // log(2 pi)

struct Params {
  Eigen::VectorXd l;
  double sf2, sn2;
};

Params unpack(const Eigen::VectorXd& theta, int d) {
  return {theta.head(d).array().exp().matrix(), std::exp(theta(d)), std::exp(theta(d + 1))};
}

Eigen::MatrixXd covariance(KernelKind kind, const Eigen::MatrixXd& X, const Params& p) {
  const Eigen::Index n = X.rows();
  Eigen::MatrixXd K(n, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    K(i, i) = p.sf2 + p.sn2;
    for (Eigen::Index j = 0; j < i; ++j)
      K(i, j) = K(j, i) = kernel_value(kind, X.row(i).transpose(), X.row(j).transpose(), p.l, p.sf2);
  }
  return K;
}

// Negative profile log likelihood (R&W eq. 2.30 with beta at its GLS estimate):
//   0.5 r' K^-1 r + sum log L_ii + n/2 log 2 pi,  r = y - H beta.
double negative_log_likelihood(KernelKind kind, const Eigen::MatrixXd& X, const Eigen::VectorXd& y,
                               const Eigen::MatrixXd& H, const Eigen::VectorXd& theta) {
  const Params p = unpack(theta, static_cast<int>(X.cols()));
  const Eigen::LLT<Eigen::MatrixXd> llt(covariance(kind, X, p));
  if (llt.info() != Eigen::Success) return 1e30;  // not positive definite: a very bad point
  const Eigen::MatrixXd KiH = llt.solve(H);
  const Eigen::LLT<Eigen::MatrixXd> hkh(H.transpose() * KiH);
  if (hkh.info() != Eigen::Success) return 1e30;
  const Eigen::VectorXd beta = hkh.solve(KiH.transpose() * y);
  const Eigen::VectorXd r = y - H * beta;
  const double logdet = 2.0 * llt.matrixL().toDenseMatrix().diagonal().array().log().sum();
  const double v = 0.5 * r.dot(llt.solve(r)) + 0.5 * logdet + 0.5 * static_cast<double>(X.rows()) * kLog2Pi;
  return std::isfinite(v) ? v : 1e30;
}

}  // namespace

Eigen::MatrixXd GaussianProcess::mean_basis(const Eigen::MatrixXd& Xn) const {
  if (options_.mean == MeanKind::constant) return Eigen::MatrixXd::Ones(Xn.rows(), 1);
  Eigen::MatrixXd H(Xn.rows(), Xn.cols() + 1);
  H.col(0).setOnes();
  H.rightCols(Xn.cols()) = Xn;
  return H;
}

void GaussianProcess::set_data(const Eigen::MatrixXd& X, const Eigen::VectorXd& y) {
  X_ = X;
  y_ = y;
  Xn_ = (X.rowwise() - x_lo_.transpose()).array().rowwise() / x_range_.transpose().array();
  yn_ = (y.array() - y_mean_) / y_sd_;
  H_ = mean_basis(Xn_);
}

void GaussianProcess::factorize() {
  const Params p = unpack(theta_, dims());
  llt_.compute(covariance(options_.kernel, Xn_, p));
  if (llt_.info() != Eigen::Success) throw DoeError("GaussianProcess: covariance matrix not positive definite");
  KinvH_ = llt_.solve(H_);
  hkh_.compute(H_.transpose() * KinvH_);
  beta_ = hkh_.solve(KinvH_.transpose() * yn_);
  alpha_ = llt_.solve(yn_ - H_ * beta_);
  lml_ = -negative_log_likelihood(options_.kernel, Xn_, yn_, H_, theta_);
}

GaussianProcess GaussianProcess::fit(const Eigen::MatrixXd& X, const Eigen::VectorXd& y, const GpOptions& o) {
  validate_or_throw(o);
  const Eigen::Index n = X.rows(), d = X.cols();
  Problems p;
  p.require(n >= 2, "GaussianProcess data (points)", n, "need at least 2");
  p.require(y.size() == n, "GaussianProcess data (responses)", y.size(), "must equal the number of points");
  p.require(d >= 1, "GaussianProcess data (inputs)", d, "need at least 1");
  p.throw_if_any();
  if (!X.allFinite() || !y.allFinite()) throw DoeError("GaussianProcess data: not all finite");
  if (o.mean == MeanKind::linear && n < d + 2)
    throw DoeError("GaussianProcess: points = " + std::to_string(n) + ": a linear mean needs at least inputs + 2");
  GaussianProcess g;
  g.options_ = o;
  g.x_lo_ = X.colwise().minCoeff().transpose();
  g.x_range_ = X.colwise().maxCoeff().transpose() - g.x_lo_;
  for (Eigen::Index j = 0; j < d; ++j)
    if (!(g.x_range_(j) > 0.0)) throw DoeError("GaussianProcess: input " + std::to_string(j + 1) + " takes a single value");
  g.y_mean_ = y.mean();
  const double var = (y.array() - g.y_mean_).square().sum() / static_cast<double>(std::max<Eigen::Index>(n - 1, 1));
  g.y_sd_ = var > 0.0 ? std::sqrt(var) : 1.0;
  g.set_data(X, y);

  // Parameter vector (log scale): d length scales, signal variance, noise variance.
  const int np = static_cast<int>(d) + (o.fit_noise ? 2 : 1);
  std::vector<double> lo(static_cast<std::size_t>(np)), hi(static_cast<std::size_t>(np));
  for (int j = 0; j < d; ++j) { lo[static_cast<std::size_t>(j)] = std::log(o.min_length); hi[static_cast<std::size_t>(j)] = std::log(o.max_length); }
  // Signal variance of the standardised response: 1e-3 .. 1e3 (beyond, the data say nothing).
  lo[static_cast<std::size_t>(d)] = std::log(1e-3);
  hi[static_cast<std::size_t>(d)] = std::log(1e3);
  const double fixed_noise = std::log(std::max(o.noise_variance / (g.y_sd_ * g.y_sd_), o.min_noise));
  if (o.fit_noise) { lo[static_cast<std::size_t>(d + 1)] = std::log(o.min_noise); hi[static_cast<std::size_t>(d + 1)] = 0.0; }
  auto full = [&](const std::vector<double>& v) {
    Eigen::VectorXd t(d + 2);
    for (int j = 0; j < np; ++j) t(j) = v[static_cast<std::size_t>(j)];
    if (!o.fit_noise) t(d + 1) = fixed_noise;
    return t;
  };
  struct Ctx {
    const GaussianProcess* g;
    std::function<Eigen::VectorXd(const std::vector<double>&)> full;
  } ctx{&g, full};
  auto objective = [](const std::vector<double>& v, std::vector<double>&, void* data) {
    const auto* c = static_cast<const Ctx*>(data);
    return negative_log_likelihood(c->g->options_.kernel, c->g->Xn_, c->g->yn_, c->g->H_, c->full(v));
  };
  std::mt19937_64 rng(o.seed);
    double best = std::numeric_limits<double>::infinity();
  std::vector<double> best_v;
  for (int s = 0; s < o.starts; ++s) {
    std::vector<double> v(static_cast<std::size_t>(np));
    for (int j = 0; j < np; ++j) {
      const auto k = static_cast<std::size_t>(j);
      // First start: length 0.3 of the range, unit signal, noise 1e-3; then uniform in the box.
      const double first = j < d ? std::log(0.3) : j == d ? 0.0 : std::log(1e-3);
      v[k] = s == 0 ? std::clamp(first, lo[k], hi[k]) : lo[k] + (hi[k] - lo[k]) * unit_uniform(rng);
    }
    nlopt::opt opt(nlopt::LN_BOBYQA, static_cast<unsigned>(np));
    opt.set_lower_bounds(lo);
    opt.set_upper_bounds(hi);
    opt.set_min_objective(objective, &ctx);
    opt.set_xtol_abs(1e-4);  // log-parameters: 1e-4 is a 0.01 % change, far below their uncertainty
    opt.set_maxeval(o.max_evaluations);
    double f = 0.0;
    try {
      opt.optimize(v, f);
    } catch (const std::runtime_error&) {
      // roundoff_limited and friends: v holds the best point reached.
    }
    std::vector<double> grad;
    f = objective(v, grad, &ctx);
    if (f < best) { best = f; best_v = v; }
  }
  g.theta_ = full(best_v);
  g.factorize();
  return g;
}

GpPrediction GaussianProcess::predict(const Eigen::VectorXd& x) const {
  if (x.size() != dims()) throw DoeError("GaussianProcess::predict: point has " + std::to_string(x.size()) + " inputs, model " + std::to_string(dims()));
  const Params p = unpack(theta_, dims());
  const Eigen::VectorXd xn = (x - x_lo_).cwiseQuotient(x_range_);
  Eigen::VectorXd k(size());
  for (int i = 0; i < size(); ++i) k(i) = kernel_value(options_.kernel, Xn_.row(i).transpose(), xn, p.l, p.sf2);
  const Eigen::RowVectorXd h = mean_basis(xn.transpose()).row(0);
  // R&W eq. 2.41-2.42: mean h'beta + k'alpha; variance k(x,x) - k'K^-1k + R'(H'K^-1H)^-1 R,
  // R = h - H'K^-1 k (the extra term accounts for estimating beta).
  const Eigen::VectorXd Kik = llt_.solve(k);
  const Eigen::VectorXd R = h.transpose() - H_.transpose() * Kik;
  double var = p.sf2 - k.dot(Kik) + R.dot(hkh_.solve(R));
  GpPrediction out;
  out.mean = y_mean_ + y_sd_ * (h.dot(beta_) + k.dot(alpha_));
  out.variance = std::max(var, 0.0) * y_sd_ * y_sd_;
  return out;
}

GpHyperparameters GaussianProcess::hyperparameters() const {
  const Params p = unpack(theta_, dims());
  return {p.l.cwiseProduct(x_range_), p.sf2 * y_sd_ * y_sd_, p.sn2 * y_sd_ * y_sd_};
}

double GaussianProcess::log_marginal_likelihood() const { return lml_; }

Eigen::VectorXd GaussianProcess::loo_residuals() const {
  const Eigen::MatrixXd Kinv = llt_.solve(Eigen::MatrixXd::Identity(size(), size()));
  return (alpha_.array() / Kinv.diagonal().array() * y_sd_).matrix();
}

double GaussianProcess::loo_rmse() const { return std::sqrt(loo_residuals().squaredNorm() / size()); }

GaussianProcess GaussianProcess::with_observation(const Eigen::VectorXd& x, double y) const {
  GaussianProcess g = *this;
  Eigen::MatrixXd X(size() + 1, dims());
  X.topRows(size()) = X_;
  X.row(size()) = x.transpose();
  Eigen::VectorXd Y(size() + 1);
  Y.head(size()) = y_;
  Y(size()) = y;
  g.set_data(X, Y);
  g.factorize();
  return g;
}

}  // namespace seedcal::doe
