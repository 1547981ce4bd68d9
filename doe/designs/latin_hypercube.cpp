#include "doe/core/random.hpp"
#include "doe/designs/latin_hypercube.hpp"

#include <limits>
#include <random>

#include "doe/core/errors.hpp"

namespace seedcal::doe {

bool LatinHypercubeOptions::IsValid(std::string* error) const {
  Problems p;
  p.require(runs >= 2, "LatinHypercubeOptions.runs", runs, "must be >= 2");
  p.require(factors >= 1, "LatinHypercubeOptions.factors", factors, "must be >= 1");
  p.require(candidates >= 1, "LatinHypercubeOptions.candidates", candidates, "must be >= 1");
  p.require(swap_iterations >= 0, "LatinHypercubeOptions.swap_iterations", swap_iterations, "must be >= 0");
  return p.report(error);
}

double min_pairwise_distance(const Eigen::MatrixXd& x) {
  double best = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < x.rows(); ++i)
    for (Eigen::Index j = i + 1; j < x.rows(); ++j) best = std::min(best, (x.row(i) - x.row(j)).squaredNorm());
  return std::sqrt(best);
}

namespace {

std::uint64_t below(std::mt19937_64& rng, std::uint64_t n) { return rng() % n; }  // bias < n/2^64
double unit(std::mt19937_64& rng) { return unit_uniform(rng); }

}  // namespace

Design latin_hypercube(const LatinHypercubeOptions& o) {
  validate_or_throw(o);
  std::mt19937_64 rng(o.seed);
  const int n = o.runs, k = o.factors;
  // Strata as integer permutations; the offsets inside strata are drawn once per candidate.
  auto realise = [&](const Eigen::MatrixXi& perm, const Eigen::MatrixXd& u) {
    Eigen::MatrixXd x(n, k);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < k; ++j) x(i, j) = -1.0 + 2.0 * (perm(i, j) + u(i, j)) / n;
    return x;
  };
  Eigen::MatrixXi best_perm;
  Eigen::MatrixXd best_u, best_x;
  double best_d = -1.0;
  for (int c = 0; c < o.candidates; ++c) {
    Eigen::MatrixXi perm(n, k);
    Eigen::MatrixXd u(n, k);
    for (int j = 0; j < k; ++j) {
      for (int i = 0; i < n; ++i) perm(i, j) = i;
      for (int i = n - 1; i > 0; --i) std::swap(perm(i, j), perm(static_cast<int>(below(rng, static_cast<std::uint64_t>(i + 1))), j));
      for (int i = 0; i < n; ++i) u(i, j) = o.centered ? 0.5 : unit(rng);
    }
    Eigen::MatrixXd x = realise(perm, u);
    const double d = min_pairwise_distance(x);
    if (d > best_d) { best_d = d; best_perm = perm; best_u = u; best_x = x; }
  }
  for (int it = 0; it < o.swap_iterations; ++it) {
    const int j = static_cast<int>(below(rng, static_cast<std::uint64_t>(k)));
    const int a = static_cast<int>(below(rng, static_cast<std::uint64_t>(n)));
    const int b = static_cast<int>(below(rng, static_cast<std::uint64_t>(n)));
    if (a == b) continue;
    std::swap(best_perm(a, j), best_perm(b, j));
    std::swap(best_u(a, j), best_u(b, j));  // the stratum offsets travel with the level
    Eigen::MatrixXd x = realise(best_perm, best_u);
    const double d = min_pairwise_distance(x);
    if (d > best_d) {
      best_d = d;
      best_x = std::move(x);
    } else {
      std::swap(best_perm(a, j), best_perm(b, j));
      std::swap(best_u(a, j), best_u(b, j));
    }
  }
  return make_design(std::move(best_x), PointType::space_filling);
}

}  // namespace seedcal::doe
