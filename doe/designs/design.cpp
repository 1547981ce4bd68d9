#include "doe/designs/design.hpp"

#include <random>
#include <utility>

#include "doe/core/errors.hpp"

namespace seedcal::doe {

const char* to_string(PointType t) {
  switch (t) {
    case PointType::factorial: return "factorial";
    case PointType::center: return "center";
    case PointType::axial: return "axial";
    case PointType::edge: return "edge";
    case PointType::space_filling: return "space_filling";
  }
  return "?";
}

std::vector<std::string> default_names(int factors, int dummies) {
  std::vector<std::string> n;
  // Appended rather than `"x" + std::to_string(i)`: GCC 12 -O3 raises a false -Wrestrict on that.
  for (int i = 1; i <= factors; ++i) n.push_back(std::string("x").append(std::to_string(i)));
  for (int i = 1; i <= dummies; ++i) n.push_back(std::string("dummy").append(std::to_string(i)));
  return n;
}

Design make_design(Eigen::MatrixXd coded, PointType type, int n_dummy) {
  Design d;
  const int cols = static_cast<int>(coded.cols());
  d.names = default_names(cols - n_dummy, n_dummy);
  d.n_dummy = n_dummy;
  d.type.assign(static_cast<std::size_t>(coded.rows()), type);
  for (int i = 0; i < coded.rows(); ++i) d.std_order.push_back(i + 1);
  d.coded = std::move(coded);
  return d;
}

void add_center_points(Design& d, int n) {
  if (n < 0) throw DoeError("center points = " + std::to_string(n) + ": must be >= 0");
  const Eigen::Index r = d.coded.rows();
  d.coded.conservativeResize(r + n, Eigen::NoChange);
  d.coded.bottomRows(n).setZero();
  for (int i = 0; i < n; ++i) {
    d.type.push_back(PointType::center);
    d.std_order.push_back(static_cast<int>(r) + i + 1);
  }
}

void randomize_run_order(Design& d, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const int n = d.runs();
  std::vector<int> perm(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) perm[static_cast<std::size_t>(i)] = i;
  for (int i = n - 1; i > 0; --i) {
    // Modulo of a 64-bit draw: the bias (< n / 2^64) is far below anything a design can notice.
    const int j = static_cast<int>(rng() % static_cast<std::uint64_t>(i + 1));
    std::swap(perm[static_cast<std::size_t>(i)], perm[static_cast<std::size_t>(j)]);
  }
  Eigen::MatrixXd c(d.coded.rows(), d.coded.cols());
  std::vector<PointType> t;
  std::vector<int> s;
  for (int i = 0; i < n; ++i) {
    const auto p = static_cast<std::size_t>(perm[static_cast<std::size_t>(i)]);
    c.row(i) = d.coded.row(static_cast<Eigen::Index>(p));
    t.push_back(d.type[p]);
    s.push_back(d.std_order[p]);
  }
  d.coded = std::move(c);
  d.type = std::move(t);
  d.std_order = std::move(s);
}

void check_factors(const std::vector<Factor>& factors, int expected) {
  Problems p;
  if (expected >= 0)
    p.require(static_cast<int>(factors.size()) == expected, "factors", factors.size(),
              "the design has " + std::to_string(expected) + " factors");
  for (const auto& f : factors) {
    p.require(!f.name.empty(), "factor name", "\"\"", "must not be empty");
    p.require(f.low < f.high, "factor " + f.name + ".low", f.low, "must be below high = " + std::to_string(f.high));
  }
  p.throw_if_any();
}

// x = centre + half_range * coded (Myers, Montgomery & Anderson-Cook, RSM, sec. 2.8).
Eigen::MatrixXd to_natural(const Eigen::MatrixXd& coded, const std::vector<Factor>& factors) {
  Eigen::MatrixXd n = coded;
  for (std::size_t j = 0; j < factors.size() && static_cast<Eigen::Index>(j) < coded.cols(); ++j) {
    const double c = 0.5 * (factors[j].low + factors[j].high);
    const double h = 0.5 * (factors[j].high - factors[j].low);
    n.col(static_cast<Eigen::Index>(j)) = (coded.col(static_cast<Eigen::Index>(j)).array() * h + c).matrix();
  }
  return n;
}

Eigen::MatrixXd to_coded(const Eigen::MatrixXd& natural, const std::vector<Factor>& factors) {
  Eigen::MatrixXd c = natural;
  for (std::size_t j = 0; j < factors.size() && static_cast<Eigen::Index>(j) < natural.cols(); ++j) {
    const double m = 0.5 * (factors[j].low + factors[j].high);
    const double h = 0.5 * (factors[j].high - factors[j].low);
    c.col(static_cast<Eigen::Index>(j)) = ((natural.col(static_cast<Eigen::Index>(j)).array() - m) / h).matrix();
  }
  return c;
}

}  // namespace seedcal::doe
