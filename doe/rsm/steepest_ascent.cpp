#include "doe/rsm/steepest_ascent.hpp"

#include <cmath>

#include "doe/core/errors.hpp"

namespace seedcal::doe {

bool SteepestAscentOptions::IsValid(std::string* error) const {
  Problems p;
  p.require(base_step > 0.0, "SteepestAscentOptions.base_step", base_step, "must be > 0");
  p.require(max_steps >= 1, "SteepestAscentOptions.max_steps", max_steps, "must be >= 1");
  p.require(bound >= 0.0, "SteepestAscentOptions.bound", bound, "must be >= 0 (0: unbounded)");
  p.require(stop_after_worse >= 1, "SteepestAscentOptions.stop_after_worse", stop_after_worse, "must be >= 1");
  p.require(base_factor >= -1, "SteepestAscentOptions.base_factor", base_factor, "must be >= 0 (or -1: largest)");
  return p.report(error);
}

Eigen::VectorXd steepest_step(const Eigen::VectorXd& b, const SteepestAscentOptions& o) {
  validate_or_throw(o);
  if (b.size() == 0) throw DoeError("steepest_step: no coefficients");
  Eigen::Index i = o.base_factor;
  if (i < 0) b.cwiseAbs().maxCoeff(&i);
  if (i >= b.size())
    throw DoeError("SteepestAscentOptions.base_factor = " + std::to_string(o.base_factor) + ": must be below " +
                   std::to_string(b.size()));
  if (b(i) == 0.0) throw DoeError("steepest_step: the base factor's coefficient is 0: no direction");
  return (o.descent ? -1.0 : 1.0) * b / std::fabs(b(i)) * o.base_step;
}

Eigen::MatrixXd steepest_path(const Eigen::VectorXd& b, const Eigen::VectorXd& origin, const SteepestAscentOptions& o) {
  const Eigen::VectorXd dx = steepest_step(b, o);
  std::vector<Eigen::VectorXd> pts;
  for (int k = 1; k <= o.max_steps; ++k) {
    const Eigen::VectorXd x = origin + k * dx;
    if (o.bound > 0.0 && x.cwiseAbs().maxCoeff() > o.bound * (1.0 + 1e-12)) break;
    pts.push_back(x);
  }
  Eigen::MatrixXd m(static_cast<Eigen::Index>(pts.size()), b.size());
  for (std::size_t k = 0; k < pts.size(); ++k) m.row(static_cast<Eigen::Index>(k)) = pts[k].transpose();
  return m;
}

PathResult follow_path(const Eigen::VectorXd& b, const Eigen::VectorXd& origin,
                       const std::function<double(const Eigen::VectorXd&)>& f, const SteepestAscentOptions& o) {
  const Eigen::MatrixXd path = steepest_path(b, origin, o);
  PathResult r;
  r.stop_reason = path.rows() < o.max_steps ? "bound" : "max steps";
  const double sign = o.descent ? -1.0 : 1.0;
  int worse = 0;
  bool below = false, above = false;
  Eigen::Index k = 0;
  for (; k < path.rows(); ++k) {
    const double y = f(path.row(k).transpose());
    r.responses.push_back(y);
    if (r.best < 0 || sign * y > sign * r.responses[static_cast<std::size_t>(r.best)]) {
      r.best = static_cast<int>(k);
      worse = 0;
    } else {
      ++worse;
    }
    below = below || (o.has_target && y <= o.target);
    above = above || (o.has_target && y >= o.target);
    if (o.has_target && below && above) { r.stop_reason = "target bracketed"; ++k; break; }
    if (worse >= o.stop_after_worse) { r.stop_reason = "no improvement"; ++k; break; }
  }
  r.points = path.topRows(k);
  return r;
}

}  // namespace seedcal::doe
