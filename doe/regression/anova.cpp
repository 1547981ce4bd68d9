#include "doe/regression/anova.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>

#include "doe/core/errors.hpp"
#include "doe/core/numbers.hpp"

namespace seedcal::doe {

namespace {

AnovaRow make_row(std::string source, int df, double ss) {
  AnovaRow r{std::move(source), df, ss, df > 0 ? ss / df : kNaN, kNaN, kNaN};
  return r;
}

void test_against(AnovaRow& r, double ms_error, int df_error) {
  if (df_error <= 0 || r.df <= 0 || !(ms_error > 0.0)) return;
  r.f = r.ms / ms_error;
  r.p = f_test_p(r.f, r.df, df_error);
}

// Pure error: rows with equal factor settings are replicates (exact equality: settings come from
// a design or a CSV, so replicated runs carry identical numbers).
std::pair<double, int> pure_error(const Eigen::MatrixXd& X, const Eigen::VectorXd& y, int* distinct) {
  std::map<std::vector<double>, std::vector<double>> groups;
  for (Eigen::Index i = 0; i < X.rows(); ++i) {
    std::vector<double> key;
    for (Eigen::Index j = 0; j < X.cols(); ++j) key.push_back(X(i, j));
    groups[key].push_back(y(i));
  }
  double ss = 0.0;
  for (const auto& [_, v] : groups) {
    double m = 0.0;
    for (double u : v) m += u;
    m /= static_cast<double>(v.size());
    for (double u : v) ss += (u - m) * (u - m);
  }
  *distinct = static_cast<int>(groups.size());
  return {ss, static_cast<int>(X.rows()) - *distinct};
}

}  // namespace

const AnovaRow& RegressionAnalysis::row(const std::string& source) const {
  for (const auto& r : anova)
    if (r.source == source) return r;
  throw DoeError("ANOVA has no row \"" + source + "\"");
}

bool RegressionAnalysis::has_row(const std::string& source) const {
  return std::any_of(anova.begin(), anova.end(), [&](const AnovaRow& r) { return r.source == source; });
}

double RegressionAnalysis::coefficient(const std::string& term) const {
  for (std::size_t j = 0; j < terms.size(); ++j)
    if (terms[j].name == term) return fit.coefficients(static_cast<Eigen::Index>(j));
  throw DoeError("model has no term \"" + term + "\"");
}

RegressionAnalysis analyze_regression(const Eigen::MatrixXd& X, const Eigen::VectorXd& y, const std::vector<Term>& terms) {
  if (terms.empty() || !terms.front().is_intercept())
    throw DoeError("analyze_regression: the first term must be the intercept");
  for (const auto& t : terms)
    if (static_cast<Eigen::Index>(t.powers.size()) != X.cols())
      throw DoeError("analyze_regression: term " + t.name + " has a different number of factors than X");
  RegressionAnalysis a;
  a.terms = terms;
  std::vector<std::string> names;
  for (const auto& t : terms) names.push_back(t.name);
  a.fit = fit_least_squares(model_matrix(terms, X), y, names);
  const auto& f = a.fit;
  const int n = f.n, p = f.parameters;
  a.mean = y.mean();
  const double sst = (y.array() - a.mean).square().sum();

  std::vector<AnovaRow> term_rows;
  double ss_model = 0.0;
  for (int j = 1; j < p; ++j) {
    term_rows.push_back(make_row(terms[static_cast<std::size_t>(j)].name, 1, f.sequential_ss(j)));
    ss_model += f.sequential_ss(j);
  }
  AnovaRow model = make_row("model", p - 1, ss_model);
  AnovaRow resid = make_row("residual", f.df_residual, f.sse);
  test_against(model, resid.ms, resid.df);
  for (auto& r : term_rows) test_against(r, resid.ms, resid.df);
  a.anova.push_back(model);
  for (auto& r : term_rows) a.anova.push_back(r);
  a.anova.push_back(resid);
  const auto [ss_pe, df_pe] = pure_error(X, y, &a.distinct_points);
  const int df_lof = a.distinct_points - p;
  if (df_pe > 0 && df_lof > 0) {
    AnovaRow lof = make_row("lack of fit", df_lof, std::max(0.0, f.sse - ss_pe));
    AnovaRow pe = make_row("pure error", df_pe, ss_pe);
    test_against(lof, pe.ms, pe.df);
    a.anova.push_back(lof);
    a.anova.push_back(pe);
  }
  a.anova.push_back(make_row("total", n - 1, sst));

  a.adjusted_ss.resize(p);
  a.adjusted_ss(0) = kNaN;
  for (int j = 1; j < p; ++j)
    a.adjusted_ss(j) = f.coefficients(j) * f.coefficients(j) / f.unscaled_covariance(j, j);
  a.r2 = sst > 0.0 ? ss_model / sst : kNaN;
  a.adj_r2 = (sst > 0.0 && f.df_residual > 0) ? 1.0 - f.mse / (sst / (n - 1)) : kNaN;
  a.press = f.press;
  a.pred_r2 = sst > 0.0 ? 1.0 - f.press / sst : kNaN;
  a.adequate_precision = f.df_residual > 0 && f.mse > 0.0
                             ? (f.fitted.maxCoeff() - f.fitted.minCoeff()) / std::sqrt(p * f.mse / n)
                             : kNaN;
  return a;
}

namespace {
std::string num(double v, int width = 12) {
  char b[64];
  if (!std::isfinite(v)) std::snprintf(b, sizeof b, "%*s", width, "");
  else std::snprintf(b, sizeof b, "%*.6g", width, v);
  return b;
}
std::string pval(double v) {
  char b[32];
  if (!std::isfinite(v)) std::snprintf(b, sizeof b, "%10s", "");
  else if (v < 1e-4) std::snprintf(b, sizeof b, "%10s", "< 0.0001");
  else std::snprintf(b, sizeof b, "%10.4f", v);
  return b;
}
std::string pad(const std::string& s, std::size_t w) { return s.size() >= w ? s + " " : s + std::string(w - s.size(), ' '); }
}  // namespace

std::string format_regression(const RegressionAnalysis& a) {
  std::size_t w = 12;
  for (const auto& t : a.terms) w = std::max(w, t.name.size() + 2);
  std::string s = "Coefficients\n" + pad("term", w) + num(kNaN).replace(0, 12, "    estimate") +
                  "   std error           t         p\n";
  for (std::size_t j = 0; j < a.terms.size(); ++j) {
    const auto i = static_cast<Eigen::Index>(j);
    s += pad(a.terms[j].name, w) + num(a.fit.coefficients(i)) + num(a.fit.standard_errors(i)) + num(a.fit.t(i)) +
         pval(a.fit.p(i)) + "\n";
  }
  s += "\nAnalysis of variance (sequential sums of squares)\n" + pad("source", w) +
       "  df           SS          MS           F         p\n";
  for (const auto& r : a.anova) {
    char df[16];
    std::snprintf(df, sizeof df, "%4d ", r.df);
    s += pad(r.source, w) + df + num(r.ss) + num(r.ms) + num(r.f) + pval(r.p) + "\n";
  }
  char tail[256];
  std::snprintf(tail, sizeof tail,
                "\nR2 %.4f   adjusted R2 %.4f   predicted R2 %.4f   PRESS %.6g   adequate precision %.3f\n", a.r2,
                a.adj_r2, a.pred_r2, a.press, a.adequate_precision);
  return s + tail;
}

}  // namespace seedcal::doe
