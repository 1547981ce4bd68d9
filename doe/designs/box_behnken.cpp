#include "doe/designs/box_behnken.hpp"

#include <vector>

#include "doe/core/errors.hpp"
#include "doe/designs/factorial.hpp"

namespace seedcal::doe {

bool BoxBehnkenOptions::IsValid(std::string* error) const {
  Problems p;
  p.require(factors >= 3 && factors <= 7, "BoxBehnkenOptions.factors", factors, "must be in [3, 7]");
  p.require(center_points >= -1, "BoxBehnkenOptions.center_points", center_points, "must be >= 0 (or -1: default)");
  return p.report(error);
}

int box_behnken_default_centers(int k) { return k <= 4 ? 3 : 6; }

Design box_behnken(const BoxBehnkenOptions& o) {
  validate_or_throw(o);
  const int k = o.factors;
  std::vector<std::vector<int>> blocks;  // 0-based factor indices
  if (k <= 5) {
    for (int i = 0; i < k; ++i)
      for (int j = i + 1; j < k; ++j) blocks.push_back({i, j});
  } else if (k == 6) {
    blocks = {{0, 1, 3}, {1, 2, 4}, {2, 3, 5}, {0, 3, 4}, {1, 4, 5}, {0, 2, 5}};
  } else {
    blocks = {{3, 4, 5}, {0, 5, 6}, {1, 4, 6}, {0, 1, 3}, {2, 3, 6}, {0, 2, 4}, {1, 2, 5}};
  }
  const int m = static_cast<int>(blocks.front().size());
  const Eigen::MatrixXd f = full_factorial_2level(m).coded;
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(blocks.size()) * f.rows(), k);
  Eigen::Index r = 0;
  for (const auto& b : blocks)
    for (Eigen::Index i = 0; i < f.rows(); ++i, ++r)
      for (int j = 0; j < m; ++j) c(r, b[static_cast<std::size_t>(j)]) = f(i, j);
  Design d = make_design(std::move(c), PointType::edge);
  add_center_points(d, o.center_points < 0 ? box_behnken_default_centers(k) : o.center_points);
  if (o.randomize) randomize_run_order(d, o.seed);
  return d;
}

}  // namespace seedcal::doe
