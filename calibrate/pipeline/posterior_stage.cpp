// After confirmation: the posterior of the kept parameters over the surrogate box
// (doe/surrogate/posterior.hpp), with a uniform prior, every target's Gaussian process refitted
// with its run-to-run noise fixed (the replicates' pure-error mean square pooled with the
// screening's estimate), and each target's laboratory uncertainty
// (`sd` over `lab_repeats`). Per kept parameter: the 95 % credible interval and whether it is
// identified (the interval at most a third of the parameter's screening range), with the reason;
// the chosen value is flagged when it lies at the edge of the surrogate box or at its limit.
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "calibrate/pipeline/pipeline.hpp"
#include "doe/rsm/level_curve.hpp"
#include "doe/surrogate/gaussian_process.hpp"
#include "doe/surrogate/posterior.hpp"

namespace seedcal {
namespace {

// A third of the screening range: what an interval may span for its parameter to be identified.
constexpr double kIdentifiedFraction = 1.0 / 3.0;
// Coded distance from the box's edge within which a value counts as lying on it (2 % of the box).
constexpr double kEdgeCoded = 0.98;

std::string fixed(double v, int digits = 3) {
  std::ostringstream o;
  o.precision(digits);
  o << v;
  return o.str();
}

// Where kept factor q's 95 % interval (box-coded ends) meets the surrogate box: `cut_*` where the
// box's edge is not the parameter's limit (the study has no runs beyond it, so the box, not the
// data, ends the interval), `at_*` where the edge is the limit itself.
struct IntervalEnds {
  bool cut_lo = false, cut_hi = false, at_min = false, at_max = false;
};

IntervalEnds interval_ends(const StudyParameter& par, const PipelineState& st, int q, double lo_coded, double hi_coded) {
  const double tiny = 1e-9 * (std::abs(par.max) + std::abs(par.min) + 1.0);
  IntervalEnds e;
  e.cut_lo = lo_coded <= -kEdgeCoded && st.box_lo(q) > par.min + tiny;
  e.cut_hi = hi_coded >= kEdgeCoded && st.box_hi(q) < par.max - tiny;
  e.at_min = lo_coded <= -kEdgeCoded && !e.cut_lo;
  e.at_max = hi_coded >= kEdgeCoded && !e.cut_hi;
  return e;
}

// The calibrated value of each kept factor (st.chosen) at the edge of its range: at its limit, at
// the edge of the surrogate box, or with the credible interval (box-coded ends) running into a
// limit (the data favour values at or beyond it).
nlohmann::json chosen_at_edge(const StudyConfig& s, const PipelineState& st, const Eigen::VectorXd& lo_coded,
                              const Eigen::VectorXd& hi_coded) {
  nlohmann::json at_edge = nlohmann::json::object();
  if (st.chosen.size() != static_cast<Eigen::Index>(s.parameters.size())) return at_edge;
  for (int q = 0; q < static_cast<int>(st.kept.size()); ++q) {
    const int j = st.kept[static_cast<std::size_t>(q)];
    const StudyParameter& par = s.parameters[static_cast<std::size_t>(j)];
    const IntervalEnds e = interval_ends(par, st, q, lo_coded(q), hi_coded(q));
    const double v = st.chosen(j), half = 0.5 * (st.box_hi(q) - st.box_lo(q));
    const double u = (v - 0.5 * (st.box_lo(q) + st.box_hi(q))) / half;
    const double span = par.max - par.min;
    if (span > 0.0 && (v - par.min <= 0.01 * span || par.max - v <= 0.01 * span))
      at_edge[par.path] = "at its limit (min " + fixed(par.min) + ", max " + fixed(par.max) + ")";
    else if (e.at_min || e.at_max)
      at_edge[par.path] = "next to its limit: the 95 % interval runs into its " +
                          std::string(e.at_max ? "max " + fixed(par.max) : "min " + fixed(par.min)) +
                          ", so the data favour values at or beyond the limit";
    else if (std::abs(u) >= kEdgeCoded)
      at_edge[par.path] = "at the edge of the surrogate box (" + fixed(st.box_lo(q)) + " .. " + fixed(st.box_hi(q)) + ")";
  }
  return at_edge;
}

}  // namespace

void refresh_edge_flags(const StudyConfig& s, PipelineState& st, StudyStore& store) {
  if (!st.posterior.is_object() || st.posterior_lo_coded.size() != static_cast<Eigen::Index>(st.kept.size())) return;
  st.posterior["at_edge"] = chosen_at_edge(s, st, st.posterior_lo_coded, st.posterior_hi_coded);
  store.set_stage(st.stage_prefix + "posterior", st.posterior);
}

nlohmann::json run_posterior(const StudyEvaluator& ev, PipelineState& st, StudyStore& store) {
  const StudyConfig& s = ev.study();
  const int k = static_cast<int>(st.kept.size());
  nlohmann::json report = {{"prior", "uniform over the surrogate box"}, {"level", 0.95}, {"targets", nlohmann::json::array()}};
  std::vector<doe::TargetEvidence> evidence;
  std::vector<std::shared_ptr<doe::GaussianProcess>> gps;
  for (std::size_t t = 0; t < s.targets.size(); ++t) {
    const StudyTarget& tg = s.targets[t];
    Eigen::MatrixXd U;
    Eigen::VectorXd y;
    gather_surrogate_data(ev, st, static_cast<int>(t), &U, &y);
    nlohmann::json tr = {{"name", tg.name}, {"runs", y.size()}};
    // The run-to-run variance: the replicates' pure-error mean square in the box, pooled with the
    // screening's estimate (its effects' error, dummy columns or residual) when the screening has
    // one, weighting each by its degrees of freedom: a handful of replicates alone can miss the
    // variance by half either way (chi-square with 6 df: sd ratio 0.62-1.6 at 90 %).
    int df = 0;
    double noise_ss = doe::pooled_replicate_variance(U, y, &df) * df;
    std::string source = df > 0 ? std::to_string(df) + " df from replicates at the design's centre and the confirmation points" : "";
    const auto& screen = store.stages().value(st.stage_prefix + "screen", nlohmann::json::object());
    if (screen.contains("targets") && t < screen["targets"].size()) {
      const auto& sc = screen["targets"][t];
      if (sc.contains("run_noise_sd") && sc.contains("run_noise_df") && sc["run_noise_df"].get<int>() > 0) {
        const int sdf = sc["run_noise_df"].get<int>();
        noise_ss += sdf * std::pow(sc["run_noise_sd"].get<double>(), 2);
        df += sdf;
        source += std::string(source.empty() ? "" : ", ") + std::to_string(sdf) + " df from the screening's effects";
      }
    }
    double noise_var = df > 0 ? noise_ss / df : 0.0;
    tr["run_noise_df"] = df;
    if (df >= 2) {
      tr["run_noise_source"] = source;
    } else {
      // Too few degrees of freedom for a variance: the screening's lower bound (a narrower
      // posterior than the data would give, and said so).
      noise_var = t < st.run_noise_var_floor.size() ? st.run_noise_var_floor[t] : 0.0;
      tr["run_noise_source"] = "the screening's lower 95 % bound (fewer than 2 degrees of freedom from replicates)";
    }
    tr["run_noise_sd"] = std::sqrt(noise_var);
    if (y.size() < 3) {
      tr["note"] = "fewer than 3 runs in the surrogate box: no posterior";
      report["targets"].push_back(tr);
      report["error"] = "target \"" + tg.name + "\" has fewer than 3 runs in the surrogate box";
      store.set_stage(st.stage_prefix + "posterior", report);
      return report;
    }
    doe::GpOptions o;
    o.seed = s.seed;
    o.fit_noise = false;
    // A deterministic scene (no replicate spread) keeps the GP's jitter as its noise.
    o.noise_variance = noise_var;
    auto gp = std::make_shared<doe::GaussianProcess>(doe::GaussianProcess::fit(U, y, o));
    gps.push_back(gp);
    doe::TargetEvidence e;
    e.response = [gp](const Eigen::VectorXd& u) { return gp->predict(u); };
    e.value = tg.value;
    e.value_variance = tg.sd > 0.0 ? tg.sd * tg.sd / tg.lab_repeats : 0.0;
    tr["value"] = tg.value;
    if (tg.sd > 0.0) {
      tr["lab_sd"] = tg.sd;
      tr["lab_repeats"] = tg.lab_repeats;
      tr["uncertainty"] = "the laboratory's sd over its repeats, and the simulation's";
    } else {
      tr["uncertainty"] = "the simulation's only: the study gives no laboratory sd for this target";
    }
    const auto hp = gp->hyperparameters();
    nlohmann::json ls = nlohmann::json::array();
    for (Eigen::Index q = 0; q < hp.length_scales.size(); ++q) ls.push_back(hp.length_scales(q));
    tr["gp_length_scales_coded"] = ls;
    evidence.push_back(e);
    report["targets"].push_back(tr);
  }

  // One target, two kept parameters: its solution curve through the confirmed point on the
  // refitted surrogate's mean (for the pick along it, curve_stage.cpp), traced once.
  if (s.targets.size() == 1 && k == 2 && !st.curve_path.usable() && st.chosen.size() == static_cast<Eigen::Index>(s.parameters.size())) {
    doe::LevelCurveOptions lo;
    lo.anchor = box_coded(st, st.chosen);
    const auto gp = gps.front();
    st.curve_path = doe::trace_level_curve([gp](const Eigen::VectorXd& u) { return gp->predict(u).mean; }, s.targets[0].value, lo);
  }
  // The test run along that curve or over the box (curve_stage.cpp), once it has run: its response
  // model (a line in the arc length, read at each point's projection onto the curve, or a plane)
  // is one more piece of evidence.
  nlohmann::json curve_entry;
  if (st.curve_scene >= 0) {
    const StudyTarget& test = s.scene_of(st.curve_scene);
    const PipelineState* sp = &st;
    // A noise-free test fits its model exactly: the mean's variance is floored at rounding.
    const double floor_var = std::pow(1e-9 * std::fabs(test.value), 2);
    doe::TargetEvidence e;
    e.response = [sp, floor_var](const Eigen::VectorXd& u) {
      doe::GpPrediction g = curve_prediction(*sp, u);
      g.variance = std::max(g.variance, floor_var);
      return g;
    };
    e.value = test.value;
    e.value_variance = test.sd > 0.0 ? test.sd * test.sd / test.lab_repeats : 0.0;
    evidence.push_back(e);
    const bool line = st.curve_mode == "curve";
    curve_entry = {{"name", test.name},
                   {"role", line ? "verification test along the solution curve" : "verification test at the box's corners"},
                   {"runs", st.curve.value("verification", nlohmann::json::object()).value("n", 0)},
                   {"run_noise_sd", st.curve.value("verification", nlohmann::json::object()).value("sd", 0.0)},
                   {"run_noise_df", st.curve_df},
                   {"run_noise_source", std::string("the residuals of the ") + (line ? "line along the curve" : "plane over the box")},
                   {"value", test.value},
                   {"response", line ? "a straight line in the arc length along the curve, at each point's projection onto it"
                                     : "a plane in the two parameters"}};
    if (test.sd > 0.0) {
      curve_entry["lab_sd"] = test.sd;
      curve_entry["uncertainty"] = "the laboratory's sd, and the fitted model's";
    } else {
      curve_entry["uncertainty"] = "the fitted model's only: the study gives no laboratory sd for this test";
    }
  }

  doe::PosteriorOptions po;
  po.lower = Eigen::VectorXd::Constant(k, -1.0);
  po.upper = Eigen::VectorXd::Constant(k, 1.0);
  po.seed = s.seed;
  const doe::Posterior p = doe::posterior(evidence, po);

  // How much each target's mean response moves over the box (the GP's mean on the posterior's
  // points), against its run-to-run sd: why a parameter is or is not identified.
  for (std::size_t t = 0; t < gps.size(); ++t) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (Eigen::Index i = 0; i < p.points.rows(); i += std::max<Eigen::Index>(1, p.points.rows() / 2000)) {
      const double m = gps[t]->predict(p.points.row(i).transpose()).mean;
      lo = std::min(lo, m);
      hi = std::max(hi, m);
    }
    report["targets"][t]["response_range_over_box"] = {lo, hi};
  }
  if (!curve_entry.is_null()) {
    report["targets"].push_back(curve_entry);
    // What the target said alone, before the test along its curve joined.
    if (st.posterior.is_object() && st.posterior.contains("calibrated_interval"))
      report["target_alone"] = {{"calibrated_interval", st.posterior["calibrated_interval"]},
                                {"identified", st.posterior["identified"]}};
  }

  // In natural units (box_point: the surrogate box's coded -1 .. 1 to the parameters' values).
  const Eigen::VectorXd lo_n = box_point(st, p.interval_lo), hi_n = box_point(st, p.interval_hi);
  const Eigen::VectorXd mode_n = box_point(st, p.mode), median_n = box_point(st, p.median);
  nlohmann::json interval = nlohmann::json::object(), identified = nlohmann::json::object(),
                 reasons = nlohmann::json::object(),
                 mode = nlohmann::json::object(), median = nlohmann::json::object(), factors = nlohmann::json::array();
  for (int q = 0; q < k; ++q) {
    const int j = st.kept[static_cast<std::size_t>(q)];
    const StudyParameter& par = s.parameters[static_cast<std::size_t>(j)];
    const double lo = lo_n(q), hi = hi_n(q);
    interval[par.path] = {lo, hi};
    mode[par.path] = mode_n(q);
    median[par.path] = median_n(q);
    factors.push_back(par.path);
    const double range = par.high - par.low, width = hi - lo;
    // An interval that runs into an edge of the box where the parameter could go on (the edge is
    // not its min or max) is cut by the box, not by the data: the study has no runs beyond it.
    const IntervalEnds ends = interval_ends(par, st, q, p.interval_lo(q), p.interval_hi(q));
    const bool ok = width <= kIdentifiedFraction * range && !ends.cut_lo && !ends.cut_hi;
    identified[par.path] = ok;
    std::string why = "95 % interval " + fixed(lo) + " .. " + fixed(hi) + ", " + fixed(100.0 * width / range, 2) +
                      " % of the screening range " + fixed(par.low) + " .. " + fixed(par.high) + " (identified: at most " +
                      fixed(100.0 * kIdentifiedFraction, 2) + " %, not cut by the surrogate box)";
    if (width > kIdentifiedFraction * range) why += ": the targets do not pin it down within their scatter";
    if (ends.cut_lo || ends.cut_hi)
      why += std::string(width > kIdentifiedFraction * range ? "; " : ": ") +
             "the interval runs into the surrogate box's edge, beyond which the study has no runs, so the data may allow values beyond it";
    reasons[par.path] = why;
  }
  report["calibrated_interval"] = interval;
  report["identified"] = identified;
  report["reasons"] = reasons;
  report["at_edge"] = chosen_at_edge(s, st, p.interval_lo, p.interval_hi);
  report["mode"] = mode;
  report["median"] = median;
  // Whether the calibrated point and the marginals' medians lie in the joint 95 % highest-density
  // region: a point outside it is among the values the data favour least (keep_pick_in_posterior).
  // Not the marginal intervals: where the posterior is flat in a parameter, its ends lie outside
  // that parameter's central interval and are favoured as much as its middle.
  nlohmann::json in_region = {{"median", doe::in_credible_region(evidence, p, p.median)}};
  if (st.chosen.size() == static_cast<Eigen::Index>(s.parameters.size()))
    in_region["calibrated"] = doe::in_credible_region(evidence, p, box_coded(st, st.chosen));
  report["in_hpd95"] = in_region;
  // The credible region for pictures (two leading factors): the density on a 41 x 41 grid over the
  // box, natural units, with the highest-density threshold of the 95 % region.
  if (k == 2) {
    doe::PosteriorOptions coarse = po;
    coarse.grid_points = 41;
    const doe::Posterior c = doe::posterior(evidence, coarse);
    nlohmann::json grid = {{"factors", factors}, {"x", nlohmann::json::array()}, {"y", nlohmann::json::array()},
                           {"weight", nlohmann::json::array()}};
    for (Eigen::Index i = 0; i < c.points.rows(); ++i) {
      const Eigen::VectorXd x = box_point(st, c.points.row(i).transpose());
      grid["x"].push_back(x(0));
      grid["y"].push_back(x(1));
      grid["weight"].push_back(c.weights(i));
    }
    grid["hpd95_threshold"] = c.hpd_threshold;
    report["region_grid"] = grid;
  }
  st.posterior = report;
  st.posterior_lo_coded = p.interval_lo;
  st.posterior_hi_coded = p.interval_hi;
  store.set_stage(st.stage_prefix + "posterior", report);
  return report;
}

}  // namespace seedcal
