// The point on the solution curve (docs/calibrate.md, "The point on the curve").
//
// One target and two kept parameters leave a curve of solutions: the direct-shear strength is met
// by a high sliding friction with a low rolling friction as well as the reverse. A second test that
// answers differently along that curve (the heap's angle answers rolling friction) can pick the
// point, as the paper's check against the piling test does by eye. Here:
//   1. the curve u(s), s in [0, 1] its normalised arc length in the box-coded surrogate box, is the
//      level set of the target's refitted surrogate through the confirmed point (posterior stage),
//      or, where that surrogate's mean misses the target everywhere in the box (a response flat
//      within its scatter), the curve of the last solve round, which chose the confirmed point;
//   2. the test (the study's `curve_test`, else the verification test with an experimental value
//      whose runs at the curve's two ends differ most, in laboratory sd when the tests give one)
//      runs once at each of `curve_points` evenly spaced values of s, under the first model;
//   3. a straight line y = a + b s is fitted to its results (doe/rsm/level_curve.hpp), and the
//      point is s* with a + b s* = the experiment (inverse prediction, Draper & Smith sec. 3.2),
//      clamped to the curve and flagged at an end; when the slope is not told from zero by a t
//      test at 95 % the confirmed point is kept and the report says so;
//   4. the line, as a function of the box through the projection onto the curve, joins the target
//      in the posterior (posterior_stage.cpp), which gives the point its interval.
// The runs count as the test's verification under the first model: its mean is the line at s*,
// its scatter the line's residual sd (verify_stage.cpp).
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <gsl/gsl_cdf.h>

#include "calibrate/pipeline/pipeline.hpp"

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
  if (!st.curve_path.usable())
    return skip("the target's surrogate does not meet the experiment along a curve in the surrogate box: there is no curve to pick along");

  const int n = s.verify.curve_points;
  const auto natural_at = [&](double sv) { return full_point(st, box_point(st, st.curve_path.at(sv))); };
  const auto dir_of = [&](int scene, int i) {
    return out_dir + "/curve/" + path_slug(s.models[static_cast<std::size_t>(st.model)].name) + "/" + path_slug(s.scene_of(scene).name) +
           "/point_" + std::to_string(i + 1);
  };
  std::vector<double> svals(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) svals[static_cast<std::size_t>(i)] = static_cast<double>(i) / (n - 1);

  // Records of the chosen test at each point (index into svals), and every run made.
  std::vector<EvaluationRecord> at(static_cast<std::size_t>(n));
  std::vector<char> have(static_cast<std::size_t>(n), 0);
  nlohmann::json pilot = nlohmann::json::array();
  int scene = candidates.front();
  if (candidates.size() > 1) {
    // The curve's two ends for every candidate; the one whose ends differ most is run along it.
    std::vector<EvalRequest> requests;
    for (const int c : candidates) {
      requests.push_back(ev.plan_one("curve", natural_at(0.0), c, st.model, dir_of(c, 0)));
      requests.push_back(ev.plan_one("curve", natural_at(1.0), c, st.model, dir_of(c, n - 1)));
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
    report["choice_rule"] = "the test whose runs at the curve's two ends differ most (in laboratory sd where the tests give one)";
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
      requests.push_back(ev.plan_one("curve", natural_at(svals[static_cast<std::size_t>(i)]), scene, st.model, dir_of(scene, i)));
      index.push_back(i);
    }
    ev.announce("curve (" + test.name + ")", static_cast<int>(requests.size()));
    const auto records = ev.run(requests);
    for (std::size_t k = 0; k < records.size(); ++k) at[static_cast<std::size_t>(index[k])] = records[k];
  }

  std::vector<double> xs, ys;
  nlohmann::json points = nlohmann::json::array(), failures = nlohmann::json::array(), samples = nlohmann::json::array(),
                 seeds = nlohmann::json::array();
  double cpu = 0.0;
  for (int i = 0; i < n; ++i) {
    const EvaluationRecord& r = at[static_cast<std::size_t>(i)];
    const double sv = svals[static_cast<std::size_t>(i)], y = record_metric(s, r);
    cpu += r.cpu_seconds;
    nlohmann::json p = {{"s", sv}, {"at", natural_of(s, st, natural_at(sv))}, {"seed", r.seed}, {"status", r.status}};
    p["value"] = std::isfinite(y) ? nlohmann::json(y) : nlohmann::json(nullptr);
    points.push_back(p);
    if (std::isfinite(y)) {
      xs.push_back(sv);
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
  report["curve_source"] = st.curve_source;
  report["points"] = points;
  if (!failures.empty()) report["failures"] = failures;
  if (xs.size() < 3) return skip("fewer than 3 of the " + std::to_string(n) + " runs along the curve gave a result: no line");

  const doe::StraightLine line = doe::fit_straight_line(xs, ys);
  const double se_b = line.df > 0 && line.sxx > 0.0 ? std::sqrt(line.sigma2 / line.sxx) : 0.0;
  const double t_crit = line.df > 0 ? gsl_cdf_tdist_Qinv(0.025, line.df) : std::numeric_limits<double>::infinity();
  // A noise-free test (residuals at rounding) answers with any slope that is not zero.
  const bool answers = se_b > 0.0 ? std::fabs(line.b) > t_crit * se_b : line.b != 0.0;
  const double s_raw = line.inverse(test.value);
  const double s_star = std::isfinite(s_raw) ? std::clamp(s_raw, 0.0, 1.0) : 0.5;
  report["line"] = {{"intercept", line.a}, {"slope", line.b}, {"slope_se", se_b}, {"residual_sd", std::sqrt(line.sigma2)},
                    {"df", line.df}, {"r2", line.r2}, {"slope_t_critical_95", std::isfinite(t_crit) ? nlohmann::json(t_crit) : nlohmann::json(nullptr)}};
  report["answers_along_curve"] = answers;
  if (!answers) {
    report["note"] = "the test's response does not change along the curve beyond its scatter (|slope| " +
                     curve_number(std::fabs(line.b)) + " <= " + curve_number(t_crit) + " x its se " + curve_number(se_b) +
                     "): the confirmed point is kept";
  } else {
    if (s_raw < 0.0 || s_raw > 1.0)
      report["at_end"] = "the line meets the experiment beyond the curve's " + std::string(s_raw < 0.0 ? "start" : "end") +
                         " (s = " + curve_number(s_raw) + "): the end is picked";
    st.chosen = natural_at(s_star);
  }
  report["s_picked"] = answers ? nlohmann::json(s_star) : nlohmann::json(nullptr);
  report["s_line_meets_experiment"] = std::isfinite(s_raw) ? nlohmann::json(s_raw) : nlohmann::json(nullptr);
  report["picked"] = natural_of(s, st, st.chosen);
  st.curve_scene = scene;
  st.curve_line = line;

  // The test's verification under the first model, from these runs: the line at the point.
  Eigen::Vector2d chosen_u;
  for (int q = 0; q < 2; ++q)
    chosen_u(q) = (st.chosen(st.kept[static_cast<std::size_t>(q)]) - 0.5 * (st.box_lo(q) + st.box_hi(q))) /
                  (0.5 * (st.box_hi(q) - st.box_lo(q)));
  const double s_at = answers ? s_star : st.curve_path.project(chosen_u);
  const doe::GpPrediction at_point = line.predict(s_at);
  const double residual_sd = std::sqrt(line.sigma2);
  nlohmann::json v = {{"test", test.name}, {"label", test.name}, {"metric", test.metric}, {"role", "verification"},
                      {"n", xs.size()}, {"samples", samples}, {"seeds", seeds}, {"cpu_seconds", cpu / n},
                      {"mean", at_point.mean}, {"sd", residual_sd}, {"sd_df", line.df}, {"mean_se", at_point.sd()},
                      {"experimental_mean", test.value},
                      {"experimental_sd", test.sd > 0.0 ? nlohmann::json(test.sd) : nlohmann::json(nullptr)},
                      {"rel_error", at_point.mean / test.value - 1.0},
                      {"within_sd", test.sd > 0.0 ? nlohmann::json(std::fabs(at_point.mean - test.value) <= test.sd) : nlohmann::json(nullptr)},
                      {"source", "the " + std::to_string(xs.size()) + " runs along the solution curve: the line fitted to them at the point, its sd the line's residual sd"}};
  if (!failures.empty()) v["failures"] = failures;
  st.curve_verification = v;
  report["verification"] = v;
  st.curve = report;
  store.set_stage(st.stage_prefix + "curve", report);
  return report;
}

}  // namespace seedcal
