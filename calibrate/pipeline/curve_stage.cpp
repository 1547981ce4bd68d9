// The point on the solution curve (docs/calibrate.md, "The point on the curve").
//
// One target and two kept parameters leave a set of solutions: the direct-shear strength is met by
// a high sliding friction with a low rolling friction as well as the reverse. A second test that
// answers differently across that set (the heap's angle answers rolling friction) can pick the
// point, as the paper's check against the piling test does by eye. Two cases:
//   - "curve": the target's surrogate refitted by the posterior meets the experiment along a curve
//     u(s) in the box-coded surrogate box (s in [0, 1] its normalised arc length, the branch
//     through the confirmed point). The test runs once at each of `curve_points` evenly spaced s;
//     its response model is a straight line y = b0 + b1 s, read at a point's projection onto the
//     curve;
//   - "region": that surrogate's mean misses the experiment everywhere in the box (the target's
//     response is flat within its scatter, so every point of the box is as good a solution). The
//     test runs at the box's four corners (and its centre for more points); its response model is
//     a plane y = b0 + b1 u1 + b2 u2.
// The model is fitted by least squares (doe/regression/least_squares.hpp). The point is where it
// meets the test's experiment: s* on the line (inverse prediction, Draper & Smith, Applied
// Regression Analysis, sec. 3.2), or on the plane the nearest point to the confirmed one,
// u0 + (y_exp - y(u0)) g / |g|^2 with g the plane's gradient; beyond the curve's ends or the box,
// the point of the curve or box whose response is nearest the experiment, with `at_end` said.
// Whether the slope terms differ from zero (t test on the line's slope, F test on the plane's, 5 %)
// is reported: with few runs a real slope can miss it, so the point moves whenever the model has
// a slope and the posterior, not the test, says how well it is pinned. The model, with the variance
// of its fitted mean, joins the target in the posterior (posterior_stage.cpp), which gives the
// point its interval. The runs count as the test's verification under this model: its mean is the
// model at the point, its sd the residual sd (verify_stage.cpp).
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <gsl/gsl_cdf.h>

#include "calibrate/pipeline/pipeline.hpp"
#include "doe/regression/least_squares.hpp"

namespace seedcal {
namespace {

std::string curve_number(double v) {
  std::ostringstream o;
  o.precision(4);
  o << v;
  return o.str();
}

nlohmann::json natural_of(const StudyConfig& s, const PipelineState& st, const Eigen::VectorXd& natural) {
  nlohmann::json p = nlohmann::json::object();
  for (const int j : st.kept) p[s.parameters[static_cast<std::size_t>(j)].path] = natural(j);
  return p;
}

// The curve test's verification read at a point: the test's model's mean there with its standard
// error, against the experiment (`sd` the laboratory's; 0 where it gives none).
void set_verification_mean(nlohmann::json& v, double mean, double mean_se, double experiment, double sd) {
  v["mean"] = mean;
  v["mean_se"] = mean_se;
  v["rel_error"] = mean / experiment - 1.0;
  v["within_sd"] = sd > 0.0 ? nlohmann::json(std::fabs(mean - experiment) <= sd) : nlohmann::json(nullptr);
}

// The region design: the four corners of the box, the (1, 1) corner last (the pilot compares the
// two ends of the diagonal), centre points between for more than four points.
Eigen::Vector2d region_point(int i, int n) {
  if (i == 0) return {-1.0, -1.0};
  if (i == n - 1) return {1.0, 1.0};
  if (i == 1) return {1.0, -1.0};
  if (i == 2) return {-1.0, 1.0};
  return {0.0, 0.0};
}

}  // namespace

std::vector<int> curve_candidates(const StudyConfig& s) {
  const int T = static_cast<int>(s.targets.size());
  std::vector<int> out, with_sd;
  for (int c = 0; c < static_cast<int>(s.checks.size()); ++c) {
    const StudyTarget& t = s.checks[static_cast<std::size_t>(c)];
    if (!s.verify.curve_test.empty()) {
      if (t.name == s.verify.curve_test) return {T + c};
      continue;
    }
    if (!t.has_value) continue;
    out.push_back(T + c);
    if (t.sd > 0.0) with_sd.push_back(T + c);
  }
  return with_sd.empty() ? out : with_sd;
}

Eigen::VectorXd curve_features(const PipelineState& st, const Eigen::VectorXd& u) {
  if (st.curve_mode == "curve") return Eigen::Vector2d(1.0, st.curve_path.project(u.head<2>()));
  return Eigen::Vector3d(1.0, u(0), u(1));
}

doe::GpPrediction curve_prediction(const PipelineState& st, const Eigen::VectorXd& u) {
  const Eigen::VectorXd f = curve_features(st, u);
  doe::GpPrediction p;
  p.mean = f.dot(st.curve_beta);
  p.variance = f.dot(st.curve_cov * f);
  return p;
}

nlohmann::json run_curve_pick(StudyEvaluator& ev, PipelineState& st, StudyStore& store, const std::string& out_dir) {
  const StudyConfig& s = ev.study();
  st.curve_scene = -1;
  nlohmann::json report = {{"points_asked", s.verify.curve_points}};
  const auto skip = [&](const std::string& why) {
    report["skipped"] = why;
    st.curve = report;
    store.set_stage(st.stage_prefix + "curve", report);
    return report;
  };
  if (s.verify.curve_points == 0) return skip("[verify] curve_points = 0");
  if (s.targets.size() != 1 || st.kept.size() != 2)
    return skip("a curve of solutions needs one target and two kept parameters (here " + std::to_string(s.targets.size()) +
                " target(s), " + std::to_string(st.kept.size()) + " kept)");
  bool all_identified = st.posterior.contains("identified");
  const nlohmann::json identified = st.posterior.value("identified", nlohmann::json::object());
  for (const auto& item : identified.items())
    all_identified = all_identified && item.value().get<bool>();
  if (all_identified) return skip("the target alone identifies both kept parameters");
  const std::vector<int> candidates = curve_candidates(s);
  if (candidates.empty()) return skip("no verification test has an experimental value to pick a point by");

  const int n = s.verify.curve_points;
  st.curve_mode = st.curve_path.usable() ? "curve" : "region";
  const bool on_curve = st.curve_mode == "curve";
  if (!on_curve && n < 4)
    return skip("the target's surrogate is flat within its scatter over the box, and a plane over the box needs at least 4 "
                "points ([verify] curve_points = " + std::to_string(n) + ")");
  report["mode"] = st.curve_mode;
  report["mode_reason"] = on_curve ? "the target's surrogate (refitted with its noise fixed) meets the experiment along a curve in the box"
                                   : "the target's surrogate (refitted with its noise fixed) misses the experiment everywhere in the box "
                                     "(a response flat within its scatter, or an experiment beyond the box): the test runs at the "
                                     "box's corners and the posterior weighs the target and the test over the whole box";
  // Box-coded position of design point i.
  const auto coded_at = [&](int i) -> Eigen::VectorXd {
    if (on_curve) return st.curve_path.at(static_cast<double>(i) / (n - 1));
    return region_point(i, n);
  };
  const auto natural_at = [&](int i) { return full_point(st, box_point(st, coded_at(i))); };
  const auto dir_of = [&](int scene, int i) {
    return out_dir + "/curve/" + path_slug(s.models[static_cast<std::size_t>(st.model)].name) + "/" + path_slug(s.scene_of(scene).name) +
           "/point_" + std::to_string(i + 1);
  };

  // Records of the chosen test at each design point.
  std::vector<EvaluationRecord> at(static_cast<std::size_t>(n));
  std::vector<char> have(static_cast<std::size_t>(n), 0);
  int scene = candidates.front();
  if (candidates.size() > 1) {
    // The design's two ends for every candidate; the one whose ends differ most runs the rest.
    nlohmann::json pilot = nlohmann::json::array();
    std::vector<EvalRequest> requests;
    for (const int c : candidates) {
      requests.push_back(ev.plan_one("curve", natural_at(0), c, st.model, dir_of(c, 0)));
      requests.push_back(ev.plan_one("curve", natural_at(n - 1), c, st.model, dir_of(c, n - 1)));
    }
    ev.announce("curve (the ends, every test)", static_cast<int>(requests.size()));
    const auto records = ev.run(requests);
    double best = -1.0;
    for (std::size_t k = 0; k < candidates.size(); ++k) {
      const StudyTarget& t = s.scene_of(candidates[k]);
      const double y0 = record_metric(s, records[2 * k]), y1 = record_metric(s, records[2 * k + 1]);
      const double scale = t.sd > 0.0 ? t.sd : std::fabs(t.value);
      const double z = std::isfinite(y0) && std::isfinite(y1) && scale > 0.0 ? std::fabs(y1 - y0) / scale : 0.0;
      pilot.push_back({{"test", t.name}, {"start", std::isfinite(y0) ? nlohmann::json(y0) : nlohmann::json(nullptr)},
                       {"end", std::isfinite(y1) ? nlohmann::json(y1) : nlohmann::json(nullptr)},
                       {"difference_in", t.sd > 0.0 ? "laboratory sd" : "fractions of the experiment"}, {"difference", z}});
      if (z > best) {
        best = z;
        scene = candidates[k];
        at.front() = records[2 * k];
        at.back() = records[2 * k + 1];
      }
    }
    have.front() = have.back() = 1;
    report["pilot"] = pilot;
    report["choice_rule"] = "the test whose runs at the design's two ends differ most (in laboratory sd where the tests give one)";
  } else {
    report["choice_rule"] = s.verify.curve_test.empty() ? "the only verification test with an experimental value"
                                                        : "named by the study ([verify] curve_test)";
  }
  const StudyTarget& test = s.scene_of(scene);
  {
    std::vector<EvalRequest> requests;
    std::vector<int> index;
    for (int i = 0; i < n; ++i) {
      if (have[static_cast<std::size_t>(i)]) continue;
      requests.push_back(ev.plan_one("curve", natural_at(i), scene, st.model, dir_of(scene, i)));
      index.push_back(i);
    }
    ev.announce("curve (" + test.name + ")", static_cast<int>(requests.size()));
    const auto records = ev.run(requests);
    for (std::size_t k = 0; k < records.size(); ++k) at[static_cast<std::size_t>(index[k])] = records[k];
  }

  const int p = on_curve ? 2 : 3;  // model terms
  std::vector<Eigen::VectorXd> rows;
  std::vector<double> ys;
  nlohmann::json points = nlohmann::json::array(), failures = nlohmann::json::array(), samples = nlohmann::json::array(),
                 seeds = nlohmann::json::array();
  double cpu = 0.0;
  for (int i = 0; i < n; ++i) {
    const EvaluationRecord& r = at[static_cast<std::size_t>(i)];
    const double y = record_metric(s, r);
    cpu += r.cpu_seconds;
    nlohmann::json pt = {{"at", natural_of(s, st, natural_at(i))}, {"seed", r.seed}, {"status", r.status}};
    if (on_curve) pt["s"] = static_cast<double>(i) / (n - 1);
    pt["value"] = std::isfinite(y) ? nlohmann::json(y) : nlohmann::json(nullptr);
    points.push_back(pt);
    if (std::isfinite(y)) {
      const Eigen::VectorXd u = coded_at(i);
      rows.push_back(on_curve ? Eigen::VectorXd(Eigen::Vector2d(1.0, static_cast<double>(i) / (n - 1)))
                              : Eigen::VectorXd(Eigen::Vector3d(1.0, u(0), u(1))));
      ys.push_back(y);
      samples.push_back(y);
      seeds.push_back(r.seed);
    } else {
      failures.push_back({{"seed", r.seed}, {"status", r.status}, {"message", r.message}});
    }
  }
  report["test"] = test.name;
  report["metric"] = test.metric;
  report["experimental_mean"] = test.value;
  report["experimental_sd"] = test.sd > 0.0 ? nlohmann::json(test.sd) : nlohmann::json(nullptr);
  report["model"] = s.models[static_cast<std::size_t>(st.model)].name;
  report["points"] = points;
  if (!failures.empty()) report["failures"] = failures;
  if (static_cast<int>(ys.size()) < p + 1)
    return skip("only " + std::to_string(ys.size()) + " of the " + std::to_string(n) + " runs gave a result: too few for a " +
                (on_curve ? "line" : "plane") + " and its scatter");

  Eigen::MatrixXd X(static_cast<Eigen::Index>(ys.size()), p);
  for (std::size_t i = 0; i < rows.size(); ++i) X.row(static_cast<Eigen::Index>(i)) = rows[i].transpose();
  const Eigen::VectorXd y = Eigen::Map<const Eigen::VectorXd>(ys.data(), static_cast<Eigen::Index>(ys.size()));
  const doe::LeastSquaresFit fit = doe::fit_least_squares(
      X, y, on_curve ? std::vector<std::string>{"intercept", "s"} : std::vector<std::string>{"intercept", "u1", "u2"});
  const int df = fit.df_residual;
  const double sigma2 = std::isfinite(fit.mse) ? fit.mse : 0.0;
  // The slope terms against zero, at 5 %: the line's t test, the plane's F test.
  double p_slope = 1.0;
  if (on_curve) {
    p_slope = fit.standard_errors(1) > 0.0 ? doe::t_test_p(fit.t(1), df) : (fit.coefficients(1) != 0.0 ? 0.0 : 1.0);
  } else {
    const Eigen::Vector2d g = fit.coefficients.tail<2>();
    const Eigen::Matrix2d cov = sigma2 * fit.unscaled_covariance.bottomRightCorner<2, 2>();
    const double f = cov.determinant() > 0.0 ? g.dot(cov.ldlt().solve(g)) / 2.0 : std::numeric_limits<double>::infinity();
    p_slope = std::isfinite(f) ? doe::f_test_p(f, 2, df) : (g.norm() > 0.0 ? 0.0 : 1.0);
  }
  const bool answers = std::isfinite(p_slope) && p_slope < 0.05;
  // The variance of the fitted mean, made as wide as the Student-t interval it stands for: the
  // posterior is Gaussian, and a residual variance on few degrees of freedom is itself uncertain
  // (factor (t_0.975,df / z_0.975)^2: 4.8 at 2 df, 1.5 at 6 df).
  const double inflation = df > 0 ? std::pow(gsl_cdf_tdist_Qinv(0.025, df) / gsl_cdf_ugaussian_Qinv(0.025), 2) : 1.0;
  st.curve_beta = fit.coefficients;
  st.curve_cov = inflation * sigma2 * fit.unscaled_covariance;
  st.curve_df = df;
  nlohmann::json coef = nlohmann::json::object(), se = nlohmann::json::object();
  for (int j = 0; j < p; ++j) {
    coef[fit.names[static_cast<std::size_t>(j)]] = fit.coefficients(j);
    se[fit.names[static_cast<std::size_t>(j)]] = fit.standard_errors(j);
  }
  const double r2 = 1.0 - fit.sse / std::max(1e-300, (y.array() - y.mean()).square().sum());
  report["response_model"] = {{"terms", on_curve ? "y = intercept + s * s_arc" : "y = intercept + u1 * u1 + u2 * u2 (box-coded)"},
                              {"coefficients", coef}, {"standard_errors", se}, {"residual_sd", std::sqrt(sigma2)}, {"df", df},
                              {"r2", r2}, {"p_slope", p_slope}, {"posterior_variance_factor", inflation}};
  report["answers"] = answers;

  const Eigen::Vector2d u0 = box_coded(st, st.chosen);
  Eigen::Vector2d u_pick = u0;
  const Eigen::VectorXd slope = fit.coefficients.tail(p - 1);
  // A slope at rounding (a response that does not change) does not move the point.
  const bool moves = slope.allFinite() && slope.norm() > 1e-9 * (std::fabs(fit.coefficients(0)) + std::fabs(test.value));
  if (!moves) {
    report["note"] = "the test's model is flat: the confirmed point is kept";
  } else if (on_curve) {
    const double s_raw = (test.value - fit.coefficients(0)) / fit.coefficients(1);
    const double s_star = std::clamp(s_raw, 0.0, 1.0);
    if (s_raw < 0.0 || s_raw > 1.0)
      report["at_end"] = "the line meets the experiment beyond the curve's " + std::string(s_raw < 0.0 ? "start" : "end") +
                         " (s = " + curve_number(s_raw) + "): the end is picked";
    report["s_picked"] = s_star;
    report["s_line_meets_experiment"] = s_raw;
    u_pick = st.curve_path.at(s_star);
  } else {
    const Eigen::Vector2d g = slope;
    const Eigen::Vector2d raw = u0 + (test.value - curve_prediction(st, u0).mean) / g.squaredNorm() * g;
    u_pick = raw;
    if (raw.cwiseAbs().maxCoeff() > 1.0) {
      // Outside the box: the point of the box whose plane value is nearest the experiment (the
      // nearest to the confirmed point among equals), on a 201 x 201 grid.
      double best = std::numeric_limits<double>::infinity(), best_d = best;
      for (int i = 0; i <= 200; ++i)
        for (int j = 0; j <= 200; ++j) {
          const Eigen::Vector2d u(-1.0 + 0.01 * i, -1.0 + 0.01 * j);
          const double miss = std::fabs(curve_prediction(st, u).mean - test.value), d = (u - u0).norm();
          if (miss < best - 1e-12 * std::fabs(test.value) || (miss <= best + 1e-12 * std::fabs(test.value) && d < best_d)) {
            best = miss;
            best_d = d;
            u_pick = u;
          }
        }
      report["at_end"] = "the plane meets the experiment outside the box (coded " + curve_number(raw(0)) + ", " +
                         curve_number(raw(1)) + "): the point of the box nearest to it in the test's response is picked";
    }
  }
  if (moves && !answers)
    report["note"] = "the slope is not told from zero at 5 % (p = " + curve_number(p_slope) +
                     "): the point rests on a response that may be flat, and the posterior's interval says how far";
  if (moves) st.chosen = full_point(st, box_point(st, u_pick));
  report["picked"] = natural_of(s, st, st.chosen);
  st.curve_scene = scene;

  // The test's verification under this model, from these runs: the model at the point.
  // Its standard error is the fit's own at the point (not widened as the posterior's is).
  const Eigen::VectorXd f_pick = curve_features(st, u_pick);
  const double here_mean = f_pick.dot(fit.coefficients);
  const double mean_se = std::sqrt(std::max(0.0, sigma2 * f_pick.dot(fit.unscaled_covariance * f_pick)));
  nlohmann::json v = {{"test", test.name}, {"label", test.name}, {"metric", test.metric}, {"role", "verification"},
                      {"n", ys.size()}, {"samples", samples}, {"seeds", seeds}, {"cpu_seconds", cpu / n},
                      {"sd", std::sqrt(sigma2)}, {"sd_df", df}, {"experimental_mean", test.value},
                      {"experimental_sd", test.sd > 0.0 ? nlohmann::json(test.sd) : nlohmann::json(nullptr)},
                      {"source", "the " + std::to_string(ys.size()) + " runs " + (on_curve ? "along the solution curve" : "at the box's corners") +
                                     ": the " + (on_curve ? "line" : "plane") + " fitted to them at the point, its sd the residual sd"}};
  set_verification_mean(v, here_mean, mean_se, test.value, test.sd);
  if (!failures.empty()) v["failures"] = failures;
  st.curve_verification = v;
  report["verification"] = v;
  st.curve = report;
  store.set_stage(st.stage_prefix + "curve", report);
  return report;
}

nlohmann::json keep_pick_in_posterior(const StudyConfig& s, PipelineState& st, StudyStore& store) {
  if (!st.curve.is_object() || !st.curve.contains("picked") || !st.curve_verification.is_object() ||
      !st.posterior.is_object() || !st.posterior.contains("calibrated_interval") || !st.posterior.contains("median") ||
      !st.posterior.contains("mode") || !st.posterior.contains("in_hpd95"))
    return nullptr;
  const nlohmann::json& in_region = st.posterior["in_hpd95"];
  if (in_region.value("calibrated", true)) return nullptr;
  // The median when it lies in the region; else (a posterior bent along a curve, whose marginal
  // medians can fall off its ridge) the point of highest density.
  const bool to_median = in_region.value("median", false);
  const nlohmann::json& interval = st.posterior["calibrated_interval"];
  const nlohmann::json& target = st.posterior[to_median ? "median" : "mode"];
  Eigen::VectorXd moved = st.chosen;
  std::string where;
  for (const int j : st.kept) {
    const std::string& path = s.parameters[static_cast<std::size_t>(j)].path;
    if (!interval.contains(path) || !target.contains(path)) return nullptr;
    const double lo = interval[path][0].get<double>(), hi = interval[path][1].get<double>(), v = st.chosen(j);
    where += (where.empty() ? "" : ", ") + path + " " + curve_number(v) + " (95 % interval " + curve_number(lo) + " .. " +
             curve_number(hi) + ")";
    moved(j) = target[path].get<double>();
  }
  const bool on_curve = st.curve_mode == "curve";
  const std::string reason =
      "the " + std::string(on_curve ? "line's" : "plane's") + " point, " + where + ", lies outside the 95 % " +
      "highest-density region that the target and the test give together: the data put it among the values they " +
      "favour least, so the calibrated point is the posterior's " +
      (to_median ? std::string("median") : std::string("mode (its median lies outside the region too)"));
  st.curve["picked_by_" + std::string(on_curve ? "line" : "plane")] = st.curve["picked"];
  st.chosen = moved;
  st.curve["picked"] = natural_of(s, st, st.chosen);
  st.curve["moved_into_posterior_region"] = reason;
  st.posterior["in_hpd95"]["calibrated"] = true;  // the median or mode the region holds

  // The test's verification from the curve's runs, read at the new point: the model's mean there,
  // and its standard error without the posterior's widening.
  const Eigen::VectorXd f = curve_features(st, box_coded(st, st.chosen));
  const double widening = st.curve["response_model"].value("posterior_variance_factor", 1.0);
  const double mean = f.dot(st.curve_beta), mean_se = std::sqrt(std::max(0.0, f.dot(st.curve_cov * f) / widening));
  nlohmann::json& v = st.curve_verification;
  set_verification_mean(v, mean, mean_se, v["experimental_mean"].get<double>(),
                        v["experimental_sd"].is_number() ? v["experimental_sd"].get<double>() : 0.0);
  v["source"] = v["source"].get<std::string>() + ", read at the posterior's " + (to_median ? "median" : "mode");
  st.curve["verification"] = v;
  store.set_stage(st.stage_prefix + "curve", st.curve);
  return {{"reason", reason}, {"picked", st.curve["picked"]}};
}

}  // namespace seedcal
