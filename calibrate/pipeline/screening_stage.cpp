// Stage 1: Plackett-Burman screening (Plackett & Burman 1946; Montgomery, DAE 8th ed., sec. 8.7.2)
// over every study parameter, each at its screening range; the effects' significance comes from the
// dummy columns (or, when a run failed, from the residual of the first-order model on the runs
// that finished). Kept: every parameter the study calibrates, plus every one significant at
// `alpha` for some target.
#include <algorithm>
#include <cmath>
#include <limits>

#include <gsl/gsl_cdf.h>

#include "calibrate/pipeline/pipeline.hpp"
#include "doe/designs/plackett_burman.hpp"
#include "doe/regression/anova.hpp"
#include "doe/regression/effects.hpp"
#include "doe/regression/model_terms.hpp"

namespace seedcal {

int primary_target(const StudyConfig& s) {
  int best = 0;
  for (std::size_t t = 1; t < s.targets.size(); ++t)
    if (s.targets[t].weight > s.targets[static_cast<std::size_t>(best)].weight) best = static_cast<int>(t);
  return best;
}

Eigen::VectorXd full_point(const PipelineState& st, const Eigen::VectorXd& kept_values) {
  Eigen::VectorXd x = st.nominal;
  for (std::size_t k = 0; k < st.kept.size(); ++k) x(st.kept[k]) = kept_values(static_cast<Eigen::Index>(k));
  return x;
}

Eigen::MatrixXd mean_responses(const StudyConfig& s, const std::vector<EvaluationRecord>& records, int points,
                               int replicates) {
  const int nt = static_cast<int>(s.targets.size());
  Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(points, nt), count = Eigen::MatrixXd::Zero(points, nt);
  for (int p = 0; p < points; ++p)
    for (int r = 0; r < replicates; ++r)
      for (int t = 0; t < nt; ++t) {
        const double v = record_metric(s, records[static_cast<std::size_t>((p * replicates + r) * nt + t)]);
        if (std::isfinite(v)) {
          sum(p, t) += v;
          count(p, t) += 1.0;
        }
      }
  Eigen::MatrixXd mean(points, nt);
  for (int p = 0; p < points; ++p)
    for (int t = 0; t < nt; ++t)
      mean(p, t) = count(p, t) > 0 ? sum(p, t) / count(p, t) : std::numeric_limits<double>::quiet_NaN();
  return mean;
}

namespace {

// Effects of every factor on one response; NaN responses (failed runs) are left out by switching
// to the first-order regression on the runs that finished.
doe::EffectsAnalysis analyze(const doe::Design& d, const Eigen::VectorXd& y, const std::vector<std::string>& names) {
  const int nf = d.factors();
  std::vector<int> ok;
  for (int i = 0; i < y.size(); ++i)
    if (std::isfinite(y(i))) ok.push_back(i);
  if (static_cast<int>(ok.size()) == y.size())
    return doe::main_effects(d.coded.leftCols(nf), y, names, d.coded.rightCols(d.n_dummy));
  Eigen::MatrixXd X(static_cast<Eigen::Index>(ok.size()), nf);
  Eigen::VectorXd yy(static_cast<Eigen::Index>(ok.size()));
  for (std::size_t k = 0; k < ok.size(); ++k) {
    X.row(static_cast<Eigen::Index>(k)) = d.coded.row(ok[k]).leftCols(nf);
    yy(static_cast<Eigen::Index>(k)) = y(ok[k]);
  }
  const auto fit = doe::analyze_regression(X, yy, doe::model_terms(doe::ModelKind::linear, names));
  doe::EffectsAnalysis a;
  a.df_error = fit.fit.df_residual;
  a.error_source = "residual (failed runs left out)";
  for (int j = 0; j < nf; ++j) {
    doe::Effect e;
    e.name = names[static_cast<std::size_t>(j)];
    e.effect = 2.0 * fit.fit.coefficients(j + 1);  // coded +-1: effect = 2 b
    e.se = 2.0 * fit.fit.standard_errors(j + 1);
    e.t = fit.fit.t(j + 1);
    e.p = fit.fit.p(j + 1);
    a.effects.push_back(e);
  }
  return a;
}

}  // namespace

nlohmann::json run_screening(StudyEvaluator& ev, PipelineState& st, StudyStore& store) {
  const StudyConfig& s = ev.study();
  const int np = static_cast<int>(s.parameters.size());
  doe::PlackettBurmanOptions o;
  o.runs = s.screen.runs;
  o.factors = np;
  const doe::Design d = doe::plackett_burman(o);
  std::vector<std::string> names;
  for (const auto& p : s.parameters) names.push_back(p.path);

  st.nominal.resize(np);
  for (int j = 0; j < np; ++j) st.nominal(j) = s.parameters[static_cast<std::size_t>(j)].nominal;

  std::vector<doe::Factor> factors;
  for (const auto& p : s.parameters) factors.push_back({p.path, p.low, p.high});
  const Eigen::MatrixXd natural = doe::to_natural(d.coded.leftCols(np), factors);
  std::vector<EvalRequest> requests;
  for (int i = 0; i < d.runs(); ++i) {
    const auto r = ev.plan("screen", natural.row(i).transpose(), s.screen.replicates);
    requests.insert(requests.end(), r.begin(), r.end());
  }
  const auto records = ev.run(requests);
  const Eigen::MatrixXd y = mean_responses(s, records, d.runs(), s.screen.replicates);

  nlohmann::json report = {{"design", "Plackett-Burman"}, {"runs", d.runs()}, {"replicates", s.screen.replicates},
                           {"dummy_columns", d.n_dummy}, {"alpha", s.screen.alpha}, {"factors", names}};
  report["coded"] = nlohmann::json::array();
  report["natural"] = nlohmann::json::array();
  for (int i = 0; i < d.runs(); ++i) {
    nlohmann::json row = nlohmann::json::array(), nat = nlohmann::json::array();
    for (int j = 0; j < d.columns(); ++j) row.push_back(d.coded(i, j));
    for (int j = 0; j < np; ++j) nat.push_back(natural(i, j));
    report["coded"].push_back(row);
    report["natural"].push_back(nat);
  }
  std::vector<bool> keep(static_cast<std::size_t>(np), false);
  for (int j = 0; j < np; ++j) keep[static_cast<std::size_t>(j)] = s.parameters[static_cast<std::size_t>(j)].calibrate;
  const int primary = primary_target(s);
  report["targets"] = nlohmann::json::array();
  st.run_noise_var_floor.assign(s.targets.size(), 0.0);
  for (std::size_t t = 0; t < s.targets.size(); ++t) {
    const Eigen::VectorXd yt = y.col(static_cast<Eigen::Index>(t));
    nlohmann::json tj = {{"name", s.targets[t].name}, {"metric", s.targets[t].metric}};
    tj["responses"] = std::vector<double>(yt.data(), yt.data() + yt.size());
    for (auto& v : tj["responses"]) if (!v.is_number() || !std::isfinite(v.get<double>())) v = nullptr;
    if ((yt.array().isFinite()).count() < np + 2) {
      tj["analysis"] = "too few finished runs for an effects analysis";
      report["targets"].push_back(tj);
      continue;
    }
    doe::EffectsAnalysis a;
    try {
      a = analyze(d, yt, names);
    } catch (const std::exception& e) {
      // Failed runs can leave a pattern of finished runs that confounds factors: no effects
      // then, as with too few runs (the failures are in the log and the store).
      tj["analysis"] = std::string("the finished runs cannot separate the effects: ") + e.what();
      report["targets"].push_back(tj);
      continue;
    }
    tj["error_source"] = a.error_source;
    tj["df_error"] = a.df_error;
    tj["effects"] = nlohmann::json::array();
    double mean = 0.0;
    int n = 0;
    for (int i = 0; i < yt.size(); ++i)
      if (std::isfinite(yt(i))) { mean += yt(i); ++n; }
    mean /= n;
    for (int j = 0; j < np; ++j) {
      const auto& e = a.effects[static_cast<std::size_t>(j)];
      // A noise-free response (a deterministic scene: the dummy columns show no error at all)
      // has se = 0 and no t test: there every effect above round-off is real.
      const bool exact = !(e.se > 0.0) && std::isfinite(e.effect);
      const bool significant = exact ? std::fabs(e.effect) > 1e-9 * std::max(std::fabs(mean), 1e-300)
                                     : std::isfinite(e.p) && e.p < s.screen.alpha;
      if (significant) keep[static_cast<std::size_t>(j)] = true;
      nlohmann::json ej = {{"factor", e.name}, {"effect", e.effect}, {"se", std::isfinite(e.se) ? nlohmann::json(e.se) : nlohmann::json(nullptr)},
                           {"t", std::isfinite(e.t) ? nlohmann::json(e.t) : nlohmann::json(nullptr)},
                           {"p", std::isfinite(e.p) ? nlohmann::json(e.p) : nlohmann::json(nullptr)},
                           {"significant", significant}};
      if (exact) ej["note"] = "no error estimate (the response has no noise): significant when not zero";
      tj["effects"].push_back(ej);
    }
    tj["mean"] = mean;
    // Run-to-run noise from the effects' error estimate (dummy columns or residual, df_error
    // degrees of freedom): an orthogonal two-level design of N points, each the mean of r
    // replicates, has se(effect) = 2 sigma_point / sqrt(N), so sigma_run^2 = r N se^2 / 4. Its
    // one-sided 95 % lower bound df s^2 / chi2_0.95(df) floors the GP's noise variance in the
    // surrogate stage, so the GP does not interpolate scatter already measured here (intrinsic
    // noise from replicates as in stochastic kriging: Ankenman, Nelson & Staum 2010).
    const double se = a.effects.empty() ? 0.0 : a.effects.front().se;
    if (std::isfinite(se) && se > 0.0 && a.df_error > 0) {
      const double n_ok = static_cast<double>(yt.array().isFinite().count());  // runs that finished
      const double var = static_cast<double>(s.screen.replicates) * n_ok * se * se / 4.0;
      const double df = static_cast<double>(a.df_error);
      st.run_noise_var_floor[t] = df * var / gsl_cdf_chisq_Qinv(0.05, df);
      tj["run_noise_sd"] = std::sqrt(var);
      tj["run_noise_sd_lower95"] = std::sqrt(st.run_noise_var_floor[t]);
      tj["run_noise_df"] = a.df_error;
    }
    if (static_cast<int>(t) == primary) {
      st.screen_mean = mean;
      st.first_order = Eigen::VectorXd::Zero(np);
      for (int j = 0; j < np; ++j) st.first_order(j) = 0.5 * a.effects[static_cast<std::size_t>(j)].effect;
    }
    report["targets"].push_back(tj);
  }
  st.kept.clear();
  for (int j = 0; j < np; ++j)
    if (keep[static_cast<std::size_t>(j)]) st.kept.push_back(j);
  if (st.first_order.size() == np) {
    Eigen::VectorXd b(static_cast<Eigen::Index>(st.kept.size()));
    for (std::size_t k = 0; k < st.kept.size(); ++k) b(static_cast<Eigen::Index>(k)) = st.first_order(st.kept[k]);
    st.first_order = b;
  } else {
    st.first_order = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(st.kept.size()));
  }
  nlohmann::json kept = nlohmann::json::array();
  for (int j : st.kept) kept.push_back(names[static_cast<std::size_t>(j)]);
  report["kept"] = kept;
  store.set_stage(st.stage_prefix + "screen", report);
  return report;
}

}  // namespace seedcal
