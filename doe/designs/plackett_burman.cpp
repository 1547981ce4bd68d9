#include "doe/designs/plackett_burman.hpp"

#include "doe/core/errors.hpp"
#include "doe/designs/factorial.hpp"

namespace seedcal::doe {

bool PlackettBurmanOptions::IsValid(std::string* error) const {
  Problems p;
  p.require(runs == 8 || runs == 12 || runs == 16 || runs == 20 || runs == 24, "PlackettBurmanOptions.runs", runs,
            "must be one of 8, 12, 16, 20, 24");
  p.require(factors >= 1 && factors <= runs - 1, "PlackettBurmanOptions.factors", factors,
            "must be in [1, runs - 1 = " + std::to_string(runs - 1) + "]");
  p.require(center_points >= 0, "PlackettBurmanOptions.center_points", center_points, "must be >= 0");
  return p.report(error);
}

std::vector<int> plackett_burman_generator(int runs) {
  // Plackett & Burman (1946), as reprinted in Montgomery DAE Table 8.23 and the NIST/SEMATECH
  // e-Handbook of Statistical Methods, sec. 5.3.3.5.
  auto parse = [](const char* s) {
    std::vector<int> g;
    for (; *s; ++s) g.push_back(*s == '+' ? 1 : -1);
    return g;
  };
  switch (runs) {
    case 12: return parse("++-+++---+-");
    case 20: return parse("++--++++-+-+----++-");
    case 24: return parse("+++++-+-++--++--+-+----");
    default: throw DoeError("plackett_burman_generator: runs = " + std::to_string(runs) + ": must be 12, 20 or 24");
  }
}

namespace {

// All 2^m - 1 columns of the 2^m factorial: the m main-effect columns first, then the interaction
// columns in order of the binary subset index (for m = 3: A B C AB AC BC ABC, i.e. the 2^(7-4)
// design with D = AB, E = AC, F = BC, G = ABC).
Eigen::MatrixXd saturated_factorial(int m) {
  const Eigen::MatrixXd base = full_factorial_2level(m).coded;
  Eigen::MatrixXd c(base.rows(), (1 << m) - 1);
  int col = 0;
  for (int j = 0; j < m; ++j) c.col(col++) = base.col(j);
  for (int order = 2; order <= m; ++order)
    for (int s = 1; s < (1 << m); ++s) {
      if (__builtin_popcount(static_cast<unsigned>(s)) != order) continue;
      std::vector<int> cols;
      for (int j = 0; j < m; ++j)
        if (s & (1 << j)) cols.push_back(j);
      c.col(col++) = interaction_column(base, cols);
    }
  return c;
}

Eigen::MatrixXd cyclic(int runs) {
  const std::vector<int> g = plackett_burman_generator(runs);
  const int m = runs - 1;
  Eigen::MatrixXd c(runs, m);
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) c(i, j) = g[static_cast<std::size_t>(((j - i) % m + m) % m)];
  c.row(m).setConstant(-1.0);
  return c;
}

}  // namespace

Design plackett_burman(const PlackettBurmanOptions& o) {
  validate_or_throw(o);
  Eigen::MatrixXd c = o.runs == 8 ? saturated_factorial(3) : o.runs == 16 ? saturated_factorial(4) : cyclic(o.runs);
  Design d = make_design(std::move(c), PointType::factorial, o.runs - 1 - o.factors);
  add_center_points(d, o.center_points);
  if (o.randomize) randomize_run_order(d, o.seed);
  return d;
}

}  // namespace seedcal::doe
