#include "doe/surrogate/surrogate_choice.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "doe/core/errors.hpp"

namespace seedcal::doe {

const char* to_string(SurrogateKind k) { return k == SurrogateKind::gp ? "gp" : "quadratic"; }

double SurrogateChoice::operator()(const Eigen::VectorXd& u) const {
  return kind == SurrogateKind::gp ? gp->predict(u).mean : (*quadratic)(u);
}

SurrogateChoice choose_surrogate(const Eigen::MatrixXd& X, const Eigen::VectorXd& y,
                                 const std::vector<std::string>& names,
                                 const SurrogateChoiceOptions& options) {
  if (options.model != "auto" && options.model != "quadratic" && options.model != "gp")
    throw DoeError("choose_surrogate: model '" + options.model + "' is not auto, quadratic or gp");
  const double inf = std::numeric_limits<double>::infinity();
  SurrogateChoice c;
  c.quadratic_loo_rmse = c.gp_loo_rmse = inf;
  c.terms = model_terms(ModelKind::quadratic, names);
  const auto n = static_cast<std::size_t>(y.size());
  if (options.model == "gp") {
    c.quadratic_error = "not asked for";
  } else if (n <= c.terms.size()) {
    c.quadratic_error = std::to_string(n) + " points for " + std::to_string(c.terms.size()) + " terms";
  } else {
    c.quadratic_tried = true;
    try {
      auto a = std::make_shared<RegressionAnalysis>(analyze_regression(X, y, c.terms));
      c.quadratic = std::make_shared<QuadraticSurface>(quadratic_surface(c.terms, a->fit.coefficients));
      c.quadratic_loo_rmse = std::isfinite(a->press) ? std::sqrt(a->press / static_cast<double>(n)) : inf;
      c.quadratic_fit = std::move(a);
    } catch (const std::exception& e) {
      c.quadratic_error = e.what();
    }
  }
  if (options.model == "quadratic") {
    c.gp_error = "not asked for";
  } else if (n < 3) {
    c.gp_error = std::to_string(n) + " points (at least 3)";
  } else {
    c.gp_tried = true;
    try {
      GpOptions o;
      o.seed = options.seed;
      const double y_var =
          n > 1 ? (y.array() - y.mean()).square().sum() / static_cast<double>(n - 1) : 0.0;
      if (options.noise_variance_floor > 0.0 && y_var > 0.0)
        o.min_noise = std::clamp(options.noise_variance_floor / y_var, o.min_noise, 0.9);
      c.gp = std::make_shared<GaussianProcess>(GaussianProcess::fit(X, y, o));
      c.gp_loo_rmse = c.gp->loo_rmse();
    } catch (const std::exception& e) {
      c.gp_error = e.what();
    }
  }
  if (!c.quadratic && !c.gp)
    throw DoeError("no surrogate could be fitted to " + std::to_string(n) + " points (quadratic: " +
                   c.quadratic_error + "; gp: " + c.gp_error + ")");
  const bool use_gp =
      c.gp && (!c.quadratic || c.gp_loo_rmse < c.quadratic_loo_rmse || options.model == "gp");
  c.kind = use_gp ? SurrogateKind::gp : SurrogateKind::quadratic;
  return c;
}

}  // namespace seedcal::doe
