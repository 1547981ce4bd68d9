#include "doe/designs/factorial.hpp"

#include <cctype>

#include "doe/core/errors.hpp"

namespace seedcal::doe {

Design full_factorial_2level(int k) {
  Problems p;
  p.require(k >= 1 && k <= 20, "full_factorial_2level.k", k, "must be in [1, 20]");
  p.throw_if_any();
  const Eigen::Index n = Eigen::Index{1} << k;
  Eigen::MatrixXd c(n, k);
  for (Eigen::Index i = 0; i < n; ++i)
    for (int j = 0; j < k; ++j) c(i, j) = ((i >> j) & 1) ? 1.0 : -1.0;
  return make_design(std::move(c), PointType::factorial);
}

Eigen::VectorXd interaction_column(const Eigen::MatrixXd& coded, const std::vector<int>& columns) {
  Eigen::VectorXd v = Eigen::VectorXd::Ones(coded.rows());
  for (int j : columns) v = v.cwiseProduct(coded.col(j));
  return v;
}

Design fractional_factorial(int k, const std::vector<std::string>& generators) {
  const int p = static_cast<int>(generators.size());
  Problems pr;
  pr.require(k >= 2 && k <= 20, "fractional_factorial.k", k, "must be in [2, 20]");
  pr.require(p >= 0 && p < k, "fractional_factorial.generators (count)", p, "must be below k");
  pr.throw_if_any();
  const int base = k - p;
  Design d = full_factorial_2level(base);
  Eigen::MatrixXd c(d.coded.rows(), k);
  c.leftCols(base) = d.coded;
  std::vector<bool> defined(static_cast<std::size_t>(k), false);
  for (int j = 0; j < base; ++j) defined[static_cast<std::size_t>(j)] = true;
  for (const auto& g : generators) {
    // "D=ABC" / "D = -ABC"
    std::string s;
    for (char ch : g)
      if (!std::isspace(static_cast<unsigned char>(ch))) s += static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
    const auto eq = s.find('=');
    const std::string where = "fractional_factorial.generator \"" + g + "\"";
    if (eq != 1 || s.size() < 3) throw DoeError(where + ": must look like D=ABC or D=-ABC");
    const int target = s[0] - 'A';
    if (target < base || target >= k)
      throw DoeError(where + ": the defined factor must be one of the " + std::to_string(p) +
                     " added factors (letters " + std::string(1, static_cast<char>('A' + base)) + ".." +
                     std::string(1, static_cast<char>('A' + k - 1)) + ")");
    if (defined[static_cast<std::size_t>(target)]) throw DoeError(where + ": factor defined twice");
    std::size_t i = eq + 1;
    double sign = 1.0;
    if (s[i] == '-') { sign = -1.0; ++i; }
    std::vector<int> cols;
    for (; i < s.size(); ++i) {
      const int b = s[i] - 'A';
      if (b < 0 || b >= base) throw DoeError(where + ": may use only the base factors A.." +
                                             std::string(1, static_cast<char>('A' + base - 1)));
      cols.push_back(b);
    }
    if (cols.empty()) throw DoeError(where + ": needs at least one base factor");
    c.col(target) = sign * interaction_column(c.leftCols(base), cols);
    defined[static_cast<std::size_t>(target)] = true;
  }
  return make_design(std::move(c), PointType::factorial);
}

Design full_factorial_3level(int k) {
  Problems p;
  p.require(k >= 1 && k <= 10, "full_factorial_3level.k", k, "must be in [1, 10]");
  p.throw_if_any();
  Eigen::Index n = 1;
  for (int j = 0; j < k; ++j) n *= 3;
  Eigen::MatrixXd c(n, k);
  for (Eigen::Index i = 0; i < n; ++i) {
    Eigen::Index r = i;
    for (int j = 0; j < k; ++j) {
      c(i, j) = static_cast<double>(r % 3) - 1.0;
      r /= 3;
    }
  }
  return make_design(std::move(c), PointType::factorial);
}

}  // namespace seedcal::doe
