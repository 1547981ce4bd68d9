#pragma once
// Polynomial model terms for response-surface regression: the intercept, main effects,
// two-factor interactions and pure quadratics, named from the factor names: "intercept", "x1",
// "x1:x2", "x1^2". Terms are kept in hierarchical order (intercept, linear, interactions in
// (i, j) order, squares), the order in which sequential (type I) sums of squares are taken.
#include <string>
#include <vector>

#include <Eigen/Dense>

namespace seedcal::doe {

enum class ModelKind { linear, interaction, quadratic };
const char* to_string(ModelKind k);
// "linear", "interaction", "quadratic"; throws DoeError otherwise.
ModelKind parse_model_kind(const std::string& s);

struct Term {
  std::vector<int> powers;  // one exponent per factor; all zero for the intercept
  std::string name;
  bool is_intercept() const;
  int order() const;        // sum of the powers
};

std::vector<Term> model_terms(ModelKind kind, const std::vector<std::string>& factor_names);

// A term from a name over the factor names: "intercept", "a", "a:b", "a^2" (throws DoeError).
Term parse_term(const std::string& name, const std::vector<std::string>& factor_names);

// Row i: every term evaluated at factor settings X.row(i).
Eigen::MatrixXd model_matrix(const std::vector<Term>& terms, const Eigen::MatrixXd& X);
Eigen::RowVectorXd model_row(const std::vector<Term>& terms, const Eigen::VectorXd& x);

}  // namespace seedcal::doe
