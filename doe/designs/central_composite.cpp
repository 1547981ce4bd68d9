#include "doe/designs/central_composite.hpp"

#include <cmath>

#include "doe/core/errors.hpp"
#include "doe/designs/factorial.hpp"

namespace seedcal::doe {

bool CentralCompositeOptions::IsValid(std::string* error) const {
  Problems p;
  p.require(factors >= 2 && factors <= 10, "CentralCompositeOptions.factors", factors, "must be in [2, 10]");
  p.require(alpha >= 0.0, "CentralCompositeOptions.alpha", alpha, "must be > 0 (or 0: from the type)");
  p.require(alpha == 0.0 || type == CcdType::circumscribed, "CentralCompositeOptions.alpha", alpha,
            "may be set only for the circumscribed type");
  p.require(center_points >= 0, "CentralCompositeOptions.center_points", center_points, "must be >= 0");
  p.require(generators.size() < static_cast<std::size_t>(factors), "CentralCompositeOptions.generators (count)",
            generators.size(), "must be below factors");
  return p.report(error);
}

double rotatable_alpha(int factorial_runs) { return std::pow(static_cast<double>(factorial_runs), 0.25); }

Design central_composite(const CentralCompositeOptions& o) {
  validate_or_throw(o);
  const int k = o.factors;
  const Eigen::MatrixXd f =
      o.generators.empty() ? full_factorial_2level(k).coded : fractional_factorial(k, o.generators).coded;
  const Eigen::Index nf = f.rows();
  double alpha = o.type == CcdType::face_centered ? 1.0 : rotatable_alpha(static_cast<int>(nf));
  if (o.alpha > 0.0) alpha = o.alpha;
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(nf + 2 * k, k);
  c.topRows(nf) = f;
  for (int j = 0; j < k; ++j) {
    c(nf + 2 * j, j) = -alpha;
    c(nf + 2 * j + 1, j) = alpha;
  }
  if (o.type == CcdType::inscribed) c /= alpha;
  Design d = make_design(std::move(c), PointType::factorial);
  for (Eigen::Index i = nf; i < d.coded.rows(); ++i) d.type[static_cast<std::size_t>(i)] = PointType::axial;
  add_center_points(d, o.center_points);
  if (o.randomize) randomize_run_order(d, o.seed);
  return d;
}

}  // namespace seedcal::doe
