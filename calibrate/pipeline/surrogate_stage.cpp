// Stages 3 and 4: a response-surface design in the surrogate box (face-centred CCD for two kept
// factors, Box-Behnken for three or more, five levels for one; Montgomery, DAE 8th ed., sec.
// 11.4), a quadratic model and a Gaussian process fitted to every run on the kept subspace, the one
// with the smaller leave-one-out error chosen (quadratic: sqrt(PRESS / n), Allen 1974; GP: R&W
// eq. 5.12), and the parameters where the chosen surface meets the target(s) found with NLopt.
//   One target, several unknowns: the solutions form a curve (a surface, ...); every multi-start hit
//   is reported, for two unknowns the curve is traced (for each value of the first factor, every
//   root in the second), and the point closest to the prior (in box-coded units) is chosen; in
//   later rounds the one closest to the point confirmed last.
//   Several targets: minimise sum_t w_t (y_t(x) / T_t - 1)^2 (plus 1e-9 times the squared coded
//   distance to the prior, which only breaks ties).
// For the report (reports/, docs/reports.md) each fit also records its data (coded and natural
// inputs, observed responses), the quadratic's ANOVA rows and coefficient table, both surrogates'
// leave-one-out predictions, and each solve round a prediction grid of every target's chosen
// surrogate over the two leading kept factors (largest first-order effect; the others at the
// chosen point).
#include <algorithm>
#include <cmath>
#include <limits>

#include "calibrate/pipeline/pipeline.hpp"
#include "doe/designs/box_behnken.hpp"
#include "doe/designs/central_composite.hpp"
#include "doe/regression/anova.hpp"
#include "doe/regression/model_terms.hpp"
#include "doe/rsm/surface_optimum.hpp"
#include "doe/rsm/level_curve.hpp"
#include "doe/surrogate/gaussian_process.hpp"
#include "doe/surrogate/surrogate_choice.hpp"
#include "store/errors.hpp"

namespace seedcal {
namespace {

// A JSON number, or null when it is not finite (no NaN reaches the store's JSON).
nlohmann::json finite_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

nlohmann::json rows_of(const Eigen::MatrixXd& m) {
  nlohmann::json out = nlohmann::json::array();
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    nlohmann::json row = nlohmann::json::array();
    for (Eigen::Index j = 0; j < m.cols(); ++j) row.push_back(finite_or_null(m(i, j)));
    out.push_back(row);
  }
  return out;
}

nlohmann::json values_of(const Eigen::VectorXd& v) {
  nlohmann::json out = nlohmann::json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) out.push_back(finite_or_null(v(i)));
  return out;
}

// The ANOVA table and the coefficients with their tests, as the report prints them.
void add_regression_tables(const doe::RegressionAnalysis& a, nlohmann::json& rep) {
  nlohmann::json anova = nlohmann::json::array();
  for (const auto& r : a.anova)
    anova.push_back({{"source", r.source}, {"df", r.df}, {"ss", finite_or_null(r.ss)}, {"ms", finite_or_null(r.ms)},
                     {"f", finite_or_null(r.f)}, {"p", finite_or_null(r.p)}});
  rep["anova"] = anova;
  nlohmann::json coef = nlohmann::json::array();
  for (std::size_t j = 0; j < a.terms.size(); ++j) {
    const auto i = static_cast<Eigen::Index>(j);
    coef.push_back({{"term", a.terms[j].name}, {"estimate", finite_or_null(a.fit.coefficients(i))},
                    {"se", finite_or_null(a.fit.standard_errors(i))}, {"t", finite_or_null(a.fit.t(i))},
                    {"p", finite_or_null(a.fit.p(i))}});
  }
  rep["coefficients"] = coef;
  rep["adequate_precision"] = finite_or_null(a.adequate_precision);
  // Leave-one-out prediction of run i: y_i - e_i / (1 - h_ii) (the PRESS residual; null when h_ii = 1).
  nlohmann::json loo = nlohmann::json::array();
  for (Eigen::Index i = 0; i < a.fit.residuals.size(); ++i) {
    const double h = a.fit.leverage(i);
    loo.push_back(h < 1.0 - 1e-12 ? finite_or_null(a.fit.fitted(i) + a.fit.residuals(i) - a.fit.residuals(i) / (1.0 - h))
                                  : nlohmann::json(nullptr));
  }
  rep["loo_predicted"] = loo;
}

Eigen::VectorXd box_mid(const PipelineState& st) { return 0.5 * (st.box_lo + st.box_hi); }
Eigen::VectorXd box_half(const PipelineState& st) { return 0.5 * (st.box_hi - st.box_lo); }

struct TargetFit {
  std::string kind;             // "quadratic" or "gp"
  doe::Surface surface;         // in box-coded units
  nlohmann::json report;
};

// `noise_var_floor`: the screening's lower bound of the run-to-run noise variance (0: none). The
// choice between the quadratic and the GP is doe::choose_surrogate's; this records both fits.
TargetFit fit_target(const StudyConfig& s, const Eigen::MatrixXd& U, const Eigen::VectorXd& y,
                     const std::vector<std::string>& names, double noise_var_floor) {
  TargetFit out;
  nlohmann::json rep = {{"points", y.size()}};
  const doe::SurrogateChoice c =
      doe::choose_surrogate(U, y, names, {s.surrogate.model, s.seed, noise_var_floor});
  if (c.quadratic_fit) {
    const doe::RegressionAnalysis& a = *c.quadratic_fit;
    const double quad_cv = c.quadratic_loo_rmse;
    nlohmann::json coef = nlohmann::json::object();
    for (std::size_t j = 0; j < c.terms.size(); ++j) coef[c.terms[j].name] = a.fit.coefficients(static_cast<Eigen::Index>(j));
    rep["quadratic"] = {{"coefficients_coded", coef}, {"r2", a.r2}, {"adj_r2", a.adj_r2},
                        {"pred_r2", std::isfinite(a.pred_r2) ? nlohmann::json(a.pred_r2) : nlohmann::json(nullptr)},
                        {"sigma", a.fit.sigma},
                        {"loo_rmse", std::isfinite(quad_cv) ? nlohmann::json(quad_cv) : nlohmann::json(nullptr)}};
    add_regression_tables(a, rep["quadratic"]);
  } else if (c.quadratic_tried) {
    rep["quadratic"] = {{"error", c.quadratic_error}};
  }
  if (c.gp) {
    const auto h = c.gp->hyperparameters();
    rep["gp"] = {{"kernel", "matern52"}, {"length_scales_coded", std::vector<double>(h.length_scales.data(), h.length_scales.data() + h.length_scales.size())},
                 {"signal_sd", std::sqrt(h.signal_variance)}, {"noise_sd", std::sqrt(h.noise_variance)},
                 {"loo_rmse", c.gp_loo_rmse},
                 {"noise_floor_sd", noise_var_floor > 0.0 ? nlohmann::json(std::sqrt(noise_var_floor)) : nlohmann::json(nullptr)}};
    rep["gp"]["loo_predicted"] = values_of(y - c.gp->loo_residuals());
  } else if (c.gp_tried) {
    rep["gp"] = {{"error", c.gp_error}};
  }
  out.kind = doe::to_string(c.kind);
  out.surface = [c](const Eigen::VectorXd& u) { return c(u); };
  rep["chosen"] = out.kind;
  rep["choice_rule"] = s.surrogate.model == "auto" ? "smaller leave-one-out RMSE" : "set by the study";
  rep["data"] = {{"coded", rows_of(U)}, {"observed", values_of(y)}};
  out.report = rep;
  return out;
}

// For two unknowns: the curve f(u) = target across the box (doe/rsm/level_curve.hpp), the branch
// through the chosen point, in natural units and in order along the curve.
nlohmann::json trace_curve(const doe::Surface& f, double target, const Eigen::VectorXd& chosen_u, const PipelineState& st,
                           const StudyConfig& s) {
  doe::LevelCurveOptions o;
  o.anchor = chosen_u.head<2>();
  const doe::CurvePath path = doe::trace_level_curve(f, target, o);
  nlohmann::json pts = nlohmann::json::array();
  const Eigen::VectorXd mid = box_mid(st), half = box_half(st);
  for (const Eigen::Vector2d& u : path.points())
    pts.push_back({{s.parameters[static_cast<std::size_t>(st.kept[0])].path, mid(0) + half(0) * u(0)},
                   {s.parameters[static_cast<std::size_t>(st.kept[1])].path, mid(1) + half(1) * u(1)}});
  return pts;
}

// Predictions of every target's chosen surrogate over the two leading kept factors (31 x 31 points
// across the box; one factor: 101 points), the other kept factors at the chosen point: the
// report's contour plot. "Leading": the largest first-order screening effects of the primary
// target (study order when there are none).
nlohmann::json surface_grid(const std::vector<TargetFit>& fits, const PipelineState& st, const StudyConfig& s,
                            const std::vector<std::string>& names, const Eigen::VectorXd& chosen_u) {
  const auto k = static_cast<int>(names.size());
  std::vector<int> order(static_cast<std::size_t>(k));
  for (int q = 0; q < k; ++q) order[static_cast<std::size_t>(q)] = q;
  if (st.first_order.size() == k)
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return std::fabs(st.first_order(a)) > std::fabs(st.first_order(b)); });
  const int a = order[0], b = k > 1 ? order[1] : -1;
  const Eigen::VectorXd mid = box_mid(st), half = box_half(st);
  const int n = k > 1 ? 31 : 101;
  auto coded = [n](int i) { return -1.0 + 2.0 * i / (n - 1); };
  nlohmann::json g = {{"factors", b >= 0 ? nlohmann::json({names[static_cast<std::size_t>(a)], names[static_cast<std::size_t>(b)]})
                                         : nlohmann::json({names[static_cast<std::size_t>(a)]})}};
  nlohmann::json xs = nlohmann::json::array(), ys = nlohmann::json::array(), held = nlohmann::json::object();
  for (int i = 0; i < n; ++i) xs.push_back(mid(a) + half(a) * coded(i));
  if (b >= 0)
    for (int i = 0; i < n; ++i) ys.push_back(mid(b) + half(b) * coded(i));
  for (int q = 0; q < k; ++q)
    if (q != a && q != b) held[names[static_cast<std::size_t>(q)]] = mid(q) + half(q) * chosen_u(q);
  g["x"] = xs;
  if (b >= 0) g["y"] = ys;
  g["held"] = held;
  g["targets"] = nlohmann::json::array();
  for (std::size_t t = 0; t < fits.size(); ++t) {
    Eigen::VectorXd u = chosen_u;
    nlohmann::json z = nlohmann::json::array();
    for (int j = 0; j < (b >= 0 ? n : 1); ++j) {
      if (b >= 0) u(b) = coded(j);
      nlohmann::json row = nlohmann::json::array();
      for (int i = 0; i < n; ++i) {
        u(a) = coded(i);
        row.push_back(finite_or_null(fits[t].surface(u)));
      }
      if (b >= 0) z.push_back(row);
      else z = row;
    }
    g["targets"].push_back({{"name", s.targets[t].name}, {"target", s.targets[t].value}, {"surrogate", fits[t].kind}, {"z", z}});
  }
  return g;
}

}  // namespace

Eigen::MatrixXd surrogate_design(const StudyConfig& s, int k, std::string* name) {
  std::string unused;
  if (!name) name = &unused;
  if (k == 1) {
    *name = "five levels";
    Eigen::MatrixXd d(4 + s.surrogate.center_points, 1);
    d << -1.0, -0.5, 0.5, 1.0, Eigen::VectorXd::Zero(s.surrogate.center_points);
    return d;
  }
  if (k >= 3 && k <= 7 && s.surrogate.design != "ccd") {
    *name = "Box-Behnken";
    doe::BoxBehnkenOptions o;
    o.factors = k;
    o.center_points = s.surrogate.center_points;
    return doe::box_behnken(o).coded;
  }
  *name = "central composite (face-centred)";
  doe::CentralCompositeOptions o;
  o.factors = k;
  o.type = doe::CcdType::face_centered;
  o.center_points = s.surrogate.center_points;
  return doe::central_composite(o).coded;
}

void gather_surrogate_data(const StudyEvaluator& ev, const PipelineState& st, int target, Eigen::MatrixXd* U,
                           Eigen::VectorXd* y) {
  const StudyConfig& s = ev.study();
  const int k = static_cast<int>(st.kept.size());
  const Eigen::VectorXd mid = box_mid(st), half = box_half(st);
  std::vector<double> rows, ys;
  for (const auto& r : ev.history()) {
    if (r.stage == "screen" || r.stage == "verify" || record_target(r) != target || record_model(s, r) != st.model) continue;
    const double v = record_metric(s, r);
    if (!std::isfinite(v)) continue;
    const Eigen::VectorXd x = ev.inputs_vector(r);
    bool on = true;  // the held parameters at nominal
    for (Eigen::Index j = 0; j < x.size(); ++j)
      if (!st.is_kept(static_cast<int>(j)) && x(j) != st.nominal(j)) on = false;
    Eigen::VectorXd u(k);
    for (int q = 0; q < k; ++q) u(q) = (x(st.kept[static_cast<std::size_t>(q)]) - mid(q)) / half(q);
    if (!on || u.cwiseAbs().maxCoeff() > 1.0 + 1e-9) continue;
    rows.insert(rows.end(), u.data(), u.data() + k);
    ys.push_back(v);
  }
  const auto n = static_cast<Eigen::Index>(ys.size());
  *U = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(rows.data(), n, k);
  *y = Eigen::Map<const Eigen::VectorXd>(ys.data(), n);
}

Eigen::VectorXd box_point(const PipelineState& st, const Eigen::VectorXd& u) {
  return box_mid(st) + box_half(st).cwiseProduct(u);
}

Eigen::VectorXd box_coded(const PipelineState& st, const Eigen::VectorXd& natural) {
  Eigen::VectorXd u(static_cast<Eigen::Index>(st.kept.size()));
  for (Eigen::Index q = 0; q < u.size(); ++q) u(q) = natural(st.kept[static_cast<std::size_t>(q)]);
  return (u - box_mid(st)).cwiseQuotient(box_half(st)).cwiseMax(-1.0).cwiseMin(1.0);
}

nlohmann::json run_surrogate_design(StudyEvaluator& ev, PipelineState& st, StudyStore& store) {
  const StudyConfig& s = ev.study();
  const int k = static_cast<int>(st.kept.size());
  std::string name;
  const Eigen::MatrixXd coded = surrogate_design(s, k, &name);
  std::vector<EvalRequest> requests;
  nlohmann::json natural = nlohmann::json::array();
  for (Eigen::Index i = 0; i < coded.rows(); ++i) {
    const Eigen::VectorXd x = box_mid(st) + box_half(st).cwiseProduct(coded.row(i).transpose());
    natural.push_back(std::vector<double>(x.data(), x.data() + x.size()));
    const auto r = ev.plan("surrogate", full_point(st, x), s.surrogate.replicates);
    requests.insert(requests.end(), r.begin(), r.end());
  }
  const auto records = ev.run(requests);
  const Eigen::MatrixXd y = mean_responses(s, records, static_cast<int>(coded.rows()), s.surrogate.replicates);
  nlohmann::json report = {{"design", name}, {"runs", coded.rows()}, {"replicates", s.surrogate.replicates},
                           {"natural", natural}};
  std::vector<std::string> factor_names, target_names;
  for (int j : st.kept) factor_names.push_back(s.parameters[static_cast<std::size_t>(j)].path);
  for (const auto& t : s.targets) target_names.push_back(t.name);
  report["factors"] = factor_names;
  report["targets"] = target_names;
  report["coded"] = rows_of(coded);
  report["responses"] = nlohmann::json::array();
  for (Eigen::Index t = 0; t < y.cols(); ++t) {
    nlohmann::json col = nlohmann::json::array();
    for (Eigen::Index i = 0; i < y.rows(); ++i) col.push_back(std::isfinite(y(i, t)) ? nlohmann::json(y(i, t)) : nlohmann::json(nullptr));
    report["responses"].push_back(col);
  }
  store.set_stage(st.stage_prefix + "surrogate_design", report);
  return report;
}

nlohmann::json fit_and_solve(StudyEvaluator& ev, PipelineState& st, StudyStore& store, const std::string& label) {
  const StudyConfig& s = ev.study();
  const int k = static_cast<int>(st.kept.size());
  const Eigen::VectorXd mid = box_mid(st), half = box_half(st);
  std::vector<std::string> names;
  for (int j : st.kept) names.push_back(s.parameters[static_cast<std::size_t>(j)].path);
  std::vector<TargetFit> fits;
  nlohmann::json report = {{"label", label}, {"factors", names}, {"targets", nlohmann::json::array()}};
  for (std::size_t t = 0; t < s.targets.size(); ++t) {
    Eigen::MatrixXd U;
    Eigen::VectorXd y;
    gather_surrogate_data(ev, st, static_cast<int>(t), &U, &y);
    const double floor = t < st.run_noise_var_floor.size() ? st.run_noise_var_floor[t] : 0.0;
    try {
      fits.push_back(fit_target(s, U, y, names, floor));
    } catch (const std::exception& e) {
      // Too few runs succeeded for any surrogate: say why they failed (the first failure), not
      // only that the fit had too few points. Each failure is in study.h5 and the log.
      std::string why;
      int failed = 0;
      for (const auto& r : ev.history())
        if (record_target(r) == static_cast<int>(t) && record_model(s, r) == st.model && r.status != "ok") {
          if (why.empty()) why = r.status + ": " + r.message;
          ++failed;
        }
      throw RunFailed("target \"" + s.targets[t].name + "\": " + e.what() + " (" + std::to_string(failed) +
                      " runs of this target failed" + (why.empty() ? std::string() : "; the first: " + why) + ")");
    }
    nlohmann::json fr = fits.back().report;
    fr["name"] = s.targets[t].name;
    Eigen::MatrixXd natural(U.rows(), U.cols());
    for (Eigen::Index i = 0; i < U.rows(); ++i) natural.row(i) = box_point(st, U.row(i).transpose()).transpose();
    fr["data"]["natural"] = rows_of(natural);
    report["targets"].push_back(fr);
  }
  st.surrogate_kind = fits[static_cast<std::size_t>(primary_target(s))].kind;

  // The anchor of the choice rule: the prior in the first round; afterwards the point confirmed
  // last, so a refitted surrogate moves the answer by the smallest step that corrects the
  // confirmed error instead of jumping along the solution set.
  const bool refine = st.chosen.size() == static_cast<Eigen::Index>(s.parameters.size());
  Eigen::VectorXd prior_u(k);
  for (int q = 0; q < k; ++q) {
    const int j = st.kept[static_cast<std::size_t>(q)];
    const double anchor = refine ? st.chosen(j) : s.parameters[static_cast<std::size_t>(j)].prior;
    prior_u(q) = std::clamp((anchor - mid(q)) / half(q), -1.0, 1.0);
  }
  const doe::Surface distance = [prior_u](const Eigen::VectorXd& u) { return (u - prior_u).squaredNorm(); };
  doe::SurfaceOptimizeOptions search;
  search.lower = Eigen::VectorXd::Constant(k, -1.0);
  search.upper = Eigen::VectorXd::Constant(k, 1.0);
  search.starts = 16;
  search.seed = s.seed;
  Eigen::VectorXd chosen_u;
  nlohmann::json solution = {{"surrogate", st.surrogate_kind}};
  auto to_natural = [&](const Eigen::VectorXd& u) {
    nlohmann::json p = nlohmann::json::object();
    for (int q = 0; q < k; ++q) p[names[static_cast<std::size_t>(q)]] = mid(q) + half(q) * u(q);
    return p;
  };
  if (s.targets.size() == 1) {
    doe::TargetOptions o;
    o.search = search;
    o.target = s.targets[0].value;
    o.tolerance = 1e-6 * std::fabs(s.targets[0].value);
    o.secondary = distance;
    const auto sol = doe::solve_for_target(fits[0].surface, o);
    chosen_u = sol.chosen;
    solution["found"] = sol.found;
    solution["underdetermined"] = k > 1;
    solution["rule"] = refine ? "of the points where the surrogate meets the target, the one closest to the point confirmed last (box-coded distance)"
                              : "of the points where the surrogate meets the target, the one closest to the prior (box-coded distance)";
    solution["multistart_solutions"] = nlohmann::json::array();
    for (const auto& u : sol.solution_set) solution["multistart_solutions"].push_back(to_natural(u));
    if (k == 2) solution["curve"] = trace_curve(fits[0].surface, o.target, sol.chosen, st, s);
    if (!sol.found) solution["note"] = "the surrogate does not reach the target inside the box: the closest point is chosen";
  } else {
    std::vector<doe::Surface> fs;
    for (const auto& f : fits) fs.push_back(f.surface);
    const StudyConfig* sp = &s;
    const doe::Surface objective = [fs, sp, distance](const Eigen::VectorXd& u) {
      double sum = 0.0;
      for (std::size_t t = 0; t < fs.size(); ++t) {
        const double e = fs[t](u) / sp->targets[t].value - 1.0;
        sum += sp->targets[t].weight * e * e;
      }
      return sum + 1e-9 * distance(u);
    };
    search.maximize = false;
    const auto opt = doe::optimize_surface(objective, search);
    chosen_u = opt.x;
    solution["found"] = true;
    solution["underdetermined"] = static_cast<int>(s.targets.size()) < k;
    solution["rule"] = "minimum of the weighted sum of squared relative errors";
    solution["objective"] = opt.y;
  }
  st.chosen = full_point(st, mid + half.cwiseProduct(chosen_u));
  solution["chosen"] = to_natural(chosen_u);
  nlohmann::json predicted = nlohmann::json::object();
  for (std::size_t t = 0; t < s.targets.size(); ++t) predicted[s.targets[t].name] = fits[t].surface(chosen_u);
  solution["predicted"] = predicted;
  report["solution"] = solution;
  report["surface_grid"] = surface_grid(fits, st, s, names, chosen_u);
  st.solution = solution;
  store.set_stage(st.stage_prefix + label, report);
  return report;
}

}  // namespace seedcal
