#include "doe/regression/model_terms.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "doe/core/errors.hpp"

namespace seedcal::doe {

const char* to_string(ModelKind k) {
  switch (k) {
    case ModelKind::linear: return "linear";
    case ModelKind::interaction: return "interaction";
    case ModelKind::quadratic: return "quadratic";
  }
  return "?";
}

ModelKind parse_model_kind(const std::string& s) {
  if (s == "linear") return ModelKind::linear;
  if (s == "interaction") return ModelKind::interaction;
  if (s == "quadratic") return ModelKind::quadratic;
  throw DoeError("model = " + s + ": must be one of linear, interaction, quadratic");
}

bool Term::is_intercept() const { return order() == 0; }
int Term::order() const { return std::accumulate(powers.begin(), powers.end(), 0); }

std::vector<Term> model_terms(ModelKind kind, const std::vector<std::string>& names) {
  const int k = static_cast<int>(names.size());
  if (k < 1) throw DoeError("model_terms: factors = 0: need at least one factor");
  std::vector<Term> t;
  const std::vector<int> zero(static_cast<std::size_t>(k), 0);
  t.push_back({zero, "intercept"});
  for (int i = 0; i < k; ++i) {
    Term a{zero, names[static_cast<std::size_t>(i)]};
    a.powers[static_cast<std::size_t>(i)] = 1;
    t.push_back(a);
  }
  if (kind != ModelKind::linear)
    for (int i = 0; i < k; ++i)
      for (int j = i + 1; j < k; ++j) {
        Term a{zero, names[static_cast<std::size_t>(i)] + ":" + names[static_cast<std::size_t>(j)]};
        a.powers[static_cast<std::size_t>(i)] = 1;
        a.powers[static_cast<std::size_t>(j)] = 1;
        t.push_back(a);
      }
  if (kind == ModelKind::quadratic)
    for (int i = 0; i < k; ++i) {
      Term a{zero, names[static_cast<std::size_t>(i)] + "^2"};
      a.powers[static_cast<std::size_t>(i)] = 2;
      t.push_back(a);
    }
  return t;
}

Term parse_term(const std::string& name, const std::vector<std::string>& names) {
  Term t{std::vector<int>(names.size(), 0), name};
  if (name == "intercept") return t;
  std::size_t start = 0;
  while (start <= name.size()) {
    const std::size_t end = std::min(name.find(':', start), name.size());
    std::string part = name.substr(start, end - start);
    int power = 1;
    const auto caret = part.rfind('^');
    if (caret != std::string::npos) {
      power = std::atoi(part.c_str() + caret + 1);
      part = part.substr(0, caret);
    }
    const auto it = std::find(names.begin(), names.end(), part);
    if (it == names.end() || power < 1)
      throw DoeError("term \"" + name + "\": \"" + part + "\" is not one of the factors");
    t.powers[static_cast<std::size_t>(it - names.begin())] += power;
    start = end + 1;
  }
  return t;
}

Eigen::RowVectorXd model_row(const std::vector<Term>& terms, const Eigen::VectorXd& x) {
  Eigen::RowVectorXd r(static_cast<Eigen::Index>(terms.size()));
  for (std::size_t t = 0; t < terms.size(); ++t) {
    double v = 1.0;
    for (std::size_t j = 0; j < terms[t].powers.size(); ++j)
      for (int p = 0; p < terms[t].powers[j]; ++p) v *= x(static_cast<Eigen::Index>(j));
    r(static_cast<Eigen::Index>(t)) = v;
  }
  return r;
}

Eigen::MatrixXd model_matrix(const std::vector<Term>& terms, const Eigen::MatrixXd& X) {
  Eigen::MatrixXd M(X.rows(), static_cast<Eigen::Index>(terms.size()));
  for (Eigen::Index i = 0; i < X.rows(); ++i) M.row(i) = model_row(terms, X.row(i).transpose());
  return M;
}

}  // namespace seedcal::doe
