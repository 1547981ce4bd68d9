#pragma once
// The surrogate of an expensive response: a full quadratic response surface (least squares,
// regression/anova.hpp) or a Gaussian process (gaussian_process.hpp), whichever predicts the data
// better out of sample. Each is scored by its leave-one-out RMSE, sqrt(PRESS / n) for the
// quadratic (Myers, Montgomery & Anderson-Cook 2016, "Response Surface Methodology", sec. 2.7)
// and the GP's closed-form leave-one-out residuals (Rasmussen & Williams 2006, sec. 5.4.2); the
// smaller wins, unless the caller asks for one kind. A kind that cannot be fitted (too few points
// for the quadratic's terms, a failed GP fit) is left out with its reason.
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "doe/regression/anova.hpp"
#include "doe/rsm/surface_optimum.hpp"
#include "doe/surrogate/gaussian_process.hpp"

namespace seedcal::doe {

enum class SurrogateKind { quadratic, gp };
const char* to_string(SurrogateKind k);

struct SurrogateChoiceOptions {
  // "auto" (the smaller leave-one-out RMSE), "quadratic" or "gp".
  std::string model = "auto";
  std::uint64_t seed = 1;  // the GP's likelihood starts
  // A lower bound of the noise variance (response units^2, 0: none), e.g. measured on replicates:
  // the GP's noise may not fall below it (as a fraction of the responses' variance, at most 0.9,
  // where the data are nearly all noise), so a length scale cannot swallow the scatter.
  double noise_variance_floor = 0.0;
};

struct SurrogateChoice {
  SurrogateKind kind = SurrogateKind::quadratic;
  // The fitted candidates (null: not fitted; the reason in *_error).
  std::shared_ptr<const RegressionAnalysis> quadratic_fit;
  std::shared_ptr<const QuadraticSurface> quadratic;
  std::shared_ptr<const GaussianProcess> gp;
  double quadratic_loo_rmse = 0.0, gp_loo_rmse = 0.0;  // +inf where not fitted or not defined
  // Why a kind was not fitted; *_tried: it was attempted (enough points, asked for) and failed.
  std::string quadratic_error, gp_error;
  bool quadratic_tried = false, gp_tried = false;
  std::vector<Term> terms;  // the quadratic's terms
  // The chosen surrogate's prediction at a coded point.
  double operator()(const Eigen::VectorXd& u) const;
};

// X: points x factors (coded), y: the responses, `names` one per factor. Throws DoeError when
// neither kind can be fitted.
SurrogateChoice choose_surrogate(const Eigen::MatrixXd& X, const Eigen::VectorXd& y,
                                 const std::vector<std::string>& names,
                                 const SurrogateChoiceOptions& options);

}  // namespace seedcal::doe
