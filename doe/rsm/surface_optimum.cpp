#include "doe/rsm/surface_optimum.hpp"

#include <cmath>
#include <limits>

#include <nlopt.hpp>

#include "doe/core/errors.hpp"
#include "doe/designs/latin_hypercube.hpp"

namespace seedcal::doe {

QuadraticSurface quadratic_surface(const std::vector<Term>& terms, const Eigen::VectorXd& c) {
  if (terms.empty() || static_cast<Eigen::Index>(terms.size()) != c.size())
    throw DoeError("quadratic_surface: terms and coefficients differ");
  const auto k = static_cast<Eigen::Index>(terms.front().powers.size());
  QuadraticSurface s;
  s.b = Eigen::VectorXd::Zero(k);
  s.B = Eigen::MatrixXd::Zero(k, k);
  for (std::size_t t = 0; t < terms.size(); ++t) {
    const auto& p = terms[t].powers;
    const double v = c(static_cast<Eigen::Index>(t));
    std::vector<Eigen::Index> idx;
    for (std::size_t j = 0; j < p.size(); ++j)
      for (int r = 0; r < p[j]; ++r) idx.push_back(static_cast<Eigen::Index>(j));
    if (idx.empty()) s.b0 += v;
    else if (idx.size() == 1) s.b(idx[0]) += v;
    else if (idx.size() == 2 && idx[0] == idx[1]) s.B(idx[0], idx[0]) += v;
    else if (idx.size() == 2) { s.B(idx[0], idx[1]) += 0.5 * v; s.B(idx[1], idx[0]) += 0.5 * v; }
    else throw DoeError("quadratic_surface: term " + terms[t].name + " is of order above 2");
  }
  return s;
}

CanonicalAnalysis canonical_analysis(const QuadraticSurface& s) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(s.B);
  CanonicalAnalysis c;
  c.eigenvalues = eig.eigenvalues();
  c.eigenvectors = eig.eigenvectors();
  const double scale = std::max(c.eigenvalues.cwiseAbs().maxCoeff(), std::numeric_limits<double>::min());
  // |lambda| below 1e-8 of the largest: B is numerically singular (a stationary ridge).
  if (c.eigenvalues.cwiseAbs().minCoeff() <= 1e-8 * scale)
    throw DoeError("canonical_analysis: the second-order matrix is singular (a ridge): no unique stationary point");
  c.stationary_point = -0.5 * s.B.ldlt().solve(s.b);
  c.stationary_response = s.b0 + 0.5 * c.stationary_point.dot(s.b);
  if ((c.eigenvalues.array() < 0.0).all()) c.nature = "maximum";
  else if ((c.eigenvalues.array() > 0.0).all()) c.nature = "minimum";
  else c.nature = "saddle point";
  if (c.eigenvalues.cwiseAbs().minCoeff() < 0.05 * scale) c.nature += " (near ridge)";
  return c;
}

bool SurfaceOptimizeOptions::IsValid(std::string* error) const {
  Problems p;
  p.require(lower.size() > 0 && lower.size() == upper.size(), "SurfaceOptimizeOptions.lower/upper (size)",
            lower.size(), "must be > 0 and equal to upper's size");
  if (lower.size() == upper.size())
    for (Eigen::Index j = 0; j < lower.size(); ++j)
      p.require(lower(j) < upper(j), "SurfaceOptimizeOptions.lower[" + std::to_string(j) + "]", lower(j),
                "must be below upper = " + std::to_string(upper(j)));
  p.require(starts >= 1, "SurfaceOptimizeOptions.starts", starts, "must be >= 1");
  p.require(x_tolerance > 0.0, "SurfaceOptimizeOptions.x_tolerance", x_tolerance, "must be > 0");
  p.require(max_evaluations >= 10, "SurfaceOptimizeOptions.max_evaluations", max_evaluations, "must be >= 10");
  return p.report(error);
}

namespace {

struct Objective {
  std::function<double(const Eigen::VectorXd&)> f;
};

double trampoline(const std::vector<double>& x, std::vector<double>& /*grad*/, void* data) {
  const auto* o = static_cast<const Objective*>(data);
  const Eigen::VectorXd v = Eigen::Map<const Eigen::VectorXd>(x.data(), static_cast<Eigen::Index>(x.size()));
  const double y = o->f(v);
  return std::isfinite(y) ? y : 1e300;  // a failed evaluation is a very bad point; the search carries on
}

std::vector<double> to_std(const Eigen::VectorXd& v) { return {v.data(), v.data() + v.size()}; }
Eigen::VectorXd to_eigen(const std::vector<double>& v) {
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

// Start points: the box centre, then a seeded maximin Latin hypercube over the box.
std::vector<Eigen::VectorXd> start_points(const SurfaceOptimizeOptions& o) {
  const Eigen::VectorXd c = 0.5 * (o.lower + o.upper), h = 0.5 * (o.upper - o.lower);
  std::vector<Eigen::VectorXd> s{c};
  if (o.starts > 1) {
    LatinHypercubeOptions l;
    l.runs = std::max(2, o.starts - 1);
    l.factors = static_cast<int>(c.size());
    l.seed = o.seed;
    l.swap_iterations = 200;
    const Eigen::MatrixXd u = latin_hypercube(l).coded;
    for (Eigen::Index i = 0; i < u.rows() && static_cast<int>(s.size()) < o.starts; ++i)
      s.push_back(c + h.cwiseProduct(u.row(i).transpose()));
  }
  return s;
}

// Minimises f from x0 in the box; returns the best point NLopt reached (also after a roundoff stop).
std::pair<Eigen::VectorXd, double> local_min(nlopt::algorithm alg, const Objective& obj, const Eigen::VectorXd& x0,
                                             const SurfaceOptimizeOptions& o, const Objective* constraint = nullptr,
                                             double constraint_tol = 0.0) {
  const auto n = static_cast<unsigned>(x0.size());
  nlopt::opt opt(alg, n);
  opt.set_lower_bounds(to_std(o.lower));
  opt.set_upper_bounds(to_std(o.upper));
  opt.set_min_objective(trampoline, const_cast<Objective*>(&obj));
  if (constraint) opt.add_inequality_constraint(trampoline, const_cast<Objective*>(constraint), constraint_tol * 1e-3);
  opt.set_xtol_rel(o.x_tolerance);
  opt.set_maxeval(o.max_evaluations);
  std::vector<double> x = to_std(x0);
  double fx = std::numeric_limits<double>::infinity();
  try {
    opt.optimize(x, fx);
  } catch (const nlopt::roundoff_limited&) {
    // NLopt keeps the best point in x; precision-limited stops are normal near a flat optimum.
  } catch (const std::runtime_error&) {
  }
  std::vector<double> g;
  fx = trampoline(x, g, const_cast<Objective*>(&obj));
  return {to_eigen(x), fx};
}

}  // namespace

SurfaceOptimum optimize_surface(const Surface& f, const SurfaceOptimizeOptions& o) {
  validate_or_throw(o);
  const double sign = o.maximize ? -1.0 : 1.0;
  const Objective obj{[&](const Eigen::VectorXd& x) { return sign * f(x); }};
  SurfaceOptimum best;
  double best_v = std::numeric_limits<double>::infinity();
  for (const auto& x0 : start_points(o)) {
    const auto [x, v] = local_min(nlopt::LN_BOBYQA, obj, x0, o);
    if (v < best_v) { best_v = v; best.x = x; }
  }
  best.y = f(best.x);
  return best;
}

TargetSolution solve_for_target(const Surface& f, const TargetOptions& t) {
  validate_or_throw(t.search);
  Problems p;
  p.require(t.tolerance > 0.0, "TargetOptions.tolerance", t.tolerance, "must be > 0");
  p.throw_if_any();
  const SurfaceOptimizeOptions& o = t.search;
  const Eigen::VectorXd centre = 0.5 * (o.lower + o.upper), half = 0.5 * (o.upper - o.lower);
  const Surface secondary = t.secondary ? t.secondary : Surface([=](const Eigen::VectorXd& x) {
    return (x - centre).cwiseQuotient(half).squaredNorm();
  });
  const Objective miss{[&](const Eigen::VectorXd& x) { return std::pow(f(x) - t.target, 2); }};
  const Objective sec{[&](const Eigen::VectorXd& x) { return secondary(x); }};
  // |y - T| - tol <= 0 written as (y - T)^2 - tol^2 <= 0: one smooth constraint.
  const Objective cons{[&](const Eigen::VectorXd& x) { return std::pow(f(x) - t.target, 2) - t.tolerance * t.tolerance; }};
  TargetSolution r;
  r.underdetermined = o.lower.size() > 1;
  double closest = std::numeric_limits<double>::infinity(), best_sec = closest;
  Eigen::VectorXd closest_x;
  for (const auto& x0 : start_points(o)) {
    const auto [x1, m] = local_min(nlopt::LN_BOBYQA, miss, x0, o);
    if (m < closest) { closest = m; closest_x = x1; }
    if (std::sqrt(m) > t.tolerance) continue;
    r.solution_set.push_back(x1);
    auto [x2, s2] = local_min(nlopt::LN_COBYLA, sec, x1, o, &cons, t.tolerance * t.tolerance);
    if (std::fabs(f(x2) - t.target) > t.tolerance) { x2 = x1; s2 = secondary(x1); }
    if (s2 < best_sec) { best_sec = s2; r.chosen = x2; }
  }
  r.found = !r.solution_set.empty();
  if (!r.found) r.chosen = closest_x;
  r.y = f(r.chosen);
  r.secondary = secondary(r.chosen);
  return r;
}

}  // namespace seedcal::doe
