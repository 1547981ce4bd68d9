#pragma once
// Gaussian-process (kriging) surrogate for an expensive, noisy black-box function (Rasmussen &
// Williams, Gaussian Processes for Machine Learning, MIT Press 2006; "R&W" below).
//   y = h(x)'beta + f(x) + eps,  f ~ GP(0, k),  eps ~ N(0, sigma_n^2)
//   mean h(x): constant (ordinary kriging) or linear (universal kriging), beta by generalised
//   least squares given the kernel (R&W sec. 2.7, eq. 2.39-2.42);
//   kernels with one length scale per input (automatic relevance determination, R&W eq. 4.14, 4.17):
//     squared exponential  k = s_f^2 exp(-r^2 / 2),
//     Matern 5/2           k = s_f^2 (1 + sqrt5 r + 5 r^2 / 3) exp(-sqrt5 r),  r^2 = sum (dx_d / l_d)^2;
//   hyperparameters (l_d, s_f^2, sigma_n^2) by maximum likelihood (the profile log likelihood with
//   beta at its GLS value, R&W eq. 2.30), multi-start BOBYQA (NLopt) over log-parameters;
//   Cholesky factorisation of K + sigma_n^2 I (Eigen LLT; R&W Algorithm 2.1).
// Inputs are scaled to [0, 1] by the training data's range and the response standardised before
// fitting; every result is reported back in the caller's units.
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Dense>

namespace seedcal::doe {

enum class KernelKind { squared_exponential, matern52 };
enum class MeanKind { constant, linear };
const char* to_string(KernelKind k);
const char* to_string(MeanKind m);

struct GpOptions {
  KernelKind kernel = KernelKind::matern52;
  MeanKind mean = MeanKind::constant;
  bool fit_noise = true;          // false: noise fixed at `noise_variance` (caller's units^2)
  double noise_variance = 0.0;
  int starts = 6;                 // maximum-likelihood starts (a fixed one plus seeded random ones)
  std::uint64_t seed = 1;
  int max_evaluations = 800;      // likelihood evaluations per start
  double min_length = 1e-2;       // length-scale bounds, as fractions of each input's data range
  double max_length = 1e1;
  double min_noise = 1e-10;       // noise-variance floor as a fraction of the response variance
                                  // (also the jitter that keeps K positive definite)
  bool IsValid(std::string* error) const;
};

struct GpHyperparameters {
  Eigen::VectorXd length_scales;  // caller's input units
  double signal_variance = 0.0;   // caller's response units^2
  double noise_variance = 0.0;    // caller's response units^2
};

struct GpPrediction {
  double mean = 0.0;
  double variance = 0.0;          // of the latent f(x) (add noise_variance for a new observation)
  double sd() const;
};

class GaussianProcess {
 public:
  // Fits hyperparameters by maximum likelihood. Throws DoeError on bad options or data (fewer
  // than 2 points, non-finite values, an input column with zero range).
  static GaussianProcess fit(const Eigen::MatrixXd& X, const Eigen::VectorXd& y, const GpOptions& options);

  GpPrediction predict(const Eigen::VectorXd& x) const;
  GpHyperparameters hyperparameters() const;
  double log_marginal_likelihood() const;  // of the standardised data at the fitted parameters

  // Leave-one-out residuals y_i - mu_{-i} with the hyperparameters and mean coefficients held
  // (R&W eq. 5.12: [K^-1 r]_i / [K^-1]_ii), in response units; and their root mean square.
  Eigen::VectorXd loo_residuals() const;
  double loo_rmse() const;

  // The same hyperparameters and scaling, conditioned on one more observation (no refit): used
  // for "kriging believer" batches and to add a point between refits.
  GaussianProcess with_observation(const Eigen::VectorXd& x, double y) const;

  const Eigen::MatrixXd& inputs() const { return X_; }
  const Eigen::VectorXd& responses() const { return y_; }
  int size() const { return static_cast<int>(X_.rows()); }
  int dims() const { return static_cast<int>(X_.cols()); }
  const GpOptions& options() const { return options_; }

 private:
  GaussianProcess() = default;
  void set_data(const Eigen::MatrixXd& X, const Eigen::VectorXd& y);
  void factorize();  // from theta_: LLT, GLS beta, alpha
  Eigen::MatrixXd mean_basis(const Eigen::MatrixXd& Xn) const;

  GpOptions options_;
  Eigen::MatrixXd X_;      // caller's units
  Eigen::VectorXd y_;
  Eigen::VectorXd x_lo_, x_range_;
  double y_mean_ = 0.0, y_sd_ = 1.0;
  Eigen::MatrixXd Xn_;     // scaled to [0, 1]
  Eigen::VectorXd yn_;     // standardised
  Eigen::VectorXd theta_;  // log l_1..l_d, log s_f^2, log sigma_n^2 (scaled units)
  Eigen::LLT<Eigen::MatrixXd> llt_;
  Eigen::MatrixXd H_;      // mean basis at the data
  Eigen::VectorXd beta_;
  Eigen::VectorXd alpha_;  // K^-1 (y - H beta)
  Eigen::MatrixXd KinvH_;
  Eigen::LLT<Eigen::MatrixXd> hkh_;  // H' K^-1 H
  double lml_ = 0.0;
};

// Kernel value for two scaled points (exposed for tests).
double kernel_value(KernelKind kind, const Eigen::VectorXd& a, const Eigen::VectorXd& b,
                    const Eigen::VectorXd& length_scales, double signal_variance);

}  // namespace seedcal::doe
