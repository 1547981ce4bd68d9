// Stage 5: confirmation with fresh DEM replicates (seeds never used before) at the chosen point.
// Per target: mean, sample sd, relative error e = mean / T - 1 and its two-sided confidence
// interval e +- t_{(1+c)/2, n-1} sd / (sqrt(n) |T|) (Student t, GSL), over every replicate run at
// the point so far. The study has converged when |e| <= tolerance for every target; the interval
// is reported with it, and whether it lies inside +-tolerance too ("resolved": the replicates are
// enough to tell).
//
// Not converged, the next step depends on whether the miss is real:
// - some target's interval excludes zero (a significant miss): the replicates join the surrogate
//   data, `batch` infill points are chosen on the primary target's Gaussian process by the
//   target-matching expected improvement (doe/surrogate/acquisition.hpp), run once each, the
//   surrogates are refitted and solved again, and a new point is confirmed afresh (a solve that
//   returns the same point keeps its pool);
// - every interval holds zero (`hold_unless_significant`, the default): the data cannot tell the
//   point from one on the target, so the point is kept and the next round adds `replicates`
//   fresh runs to the same pool. Moving on such a round chases the run-to-run scatter: where the
//   response depends weakly on a parameter, a shift of the surrogate by one standard error moves
//   the solution far along its curve (docs/calibrate.md). Holding is the sequential test of a
//   stochastic root (Pasupathy & Kim, ACM TOMACS 21 (2011) 19: the root estimate moves only on
//   evidence; replicates at a fixed point shrink its interval as 1/sqrt(n)).
// Until the budget of DEM runs (every replicate counts) or the round limit is reached.
#include <cmath>
#include <cstdio>

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_statistics_double.h>

#include "calibrate/pipeline/pipeline.hpp"
#include "doe/surrogate/acquisition.hpp"
#include "doe/surrogate/gaussian_process.hpp"

namespace seedcal {
namespace {

// Runs `replicates` fresh runs at st.chosen, adds them to `pool` (the replicates at that point so
// far) and states the pooled result.
nlohmann::json confirm_at(StudyEvaluator& ev, PipelineState& st, int round, std::vector<EvaluationRecord>& pool) {
  const StudyConfig& s = ev.study();
  ev.announce("confirm round " + std::to_string(round), s.confirm.replicates * static_cast<int>(s.targets.size()));
  const auto fresh = ev.run(ev.plan("confirm", st.chosen, s.confirm.replicates));
  pool.insert(pool.end(), fresh.begin(), fresh.end());
  const auto& records = pool;
  // Every round plans the same runs (failed ones are records too): the pool holds whole rounds.
  const std::size_t per_round = static_cast<std::size_t>(s.confirm.replicates) * s.targets.size();
  nlohmann::json out = {{"round", round}, {"rounds_pooled", pool.size() / per_round}, {"targets", nlohmann::json::object()}};
  bool all_ok = true;
  st.confirmed.clear();
  for (std::size_t t = 0; t < s.targets.size(); ++t) {
    std::vector<double> v;
    std::vector<std::uint64_t> seeds;
    for (const auto& r : records)
      if (record_target(r) == static_cast<int>(t) && std::isfinite(record_metric(s, r))) {
        v.push_back(record_metric(s, r));
        seeds.push_back(r.seed);
      }
    ConfirmedTarget c;
    c.target = s.targets[t].value;
    c.samples = v;
    c.seeds = seeds;
    const std::string& metric = s.targets[t].metric;
    if (v.size() < 2) {
      c.note = "fewer than two replicates finished: nothing is confirmed";
      all_ok = false;
      out["targets"][metric] = to_json(c);
      st.confirmed[metric] = c;
      continue;
    }
    const double T = c.target;
    const double mean = gsl_stats_mean(v.data(), 1, v.size());
    const double sd = gsl_stats_sd_m(v.data(), 1, v.size(), mean);  // sample sd (n - 1)
    const double e = mean / T - 1.0;
    const double q = gsl_cdf_tdist_Pinv(0.5 * (1.0 + s.confirm.confidence), static_cast<double>(v.size() - 1));
    const double half = q * sd / (std::sqrt(static_cast<double>(v.size())) * std::fabs(T));
    ConfirmedStats& x = c.stats.emplace();
    // Replicates that would put the whole interval inside +-tolerance if the mean sat on the
    // target: n >= (t sd / (tol |T|))^2 (t from the pool's degrees of freedom: an estimate).
    const double need = std::pow(q * sd / (s.confirm.tolerance * std::fabs(T)), 2.0);
    x.replicates_to_resolve_tolerance = static_cast<long>(std::ceil(std::max(need, 2.0)));
    x.cv = sd / std::fabs(mean);
    x.mean = mean;
    x.sd = sd;
    x.rel_error = e;
    x.rel_error_ci = {e - half, e + half};
    x.confidence = s.confirm.confidence;
    x.within_tolerance = std::fabs(e) <= s.confirm.tolerance;
    x.resolved = std::fabs(e) + half <= s.confirm.tolerance;
    // The interval excludes zero: the point misses the target beyond the scatter.
    x.significant_miss = e - half > 0.0 || e + half < 0.0;
    all_ok = all_ok && std::fabs(e) <= s.confirm.tolerance;
    out["targets"][metric] = to_json(c);
    st.confirmed[metric] = c;
  }
  out["converged"] = all_ok;
  out["runs_at_point"] = pool.size();  // DEM runs at this point, every target's
  nlohmann::json at = nlohmann::json::object();
  for (std::size_t p = 0; p < s.parameters.size(); ++p) at[s.parameters[p].path] = st.chosen(static_cast<Eigen::Index>(p));
  out["point"] = at;
  st.converged = all_ok;
  return out;
}

// Whether a round's pooled result shows a significant miss on some target. A target with fewer
// than two finished replicates has no interval: the point is moved (nothing supports it).
bool significant_miss(const nlohmann::json& round) {
  for (const auto& c : round["targets"])
    if (!c.contains("significant_miss") || c["significant_miss"].get<bool>()) return true;
  return false;
}

}  // namespace

nlohmann::json run_confirmation(StudyEvaluator& ev, PipelineState& st, StudyStore& store) {
  const StudyConfig& s = ev.study();
  const int nt = static_cast<int>(s.targets.size());
  nlohmann::json report = {{"tolerance", s.confirm.tolerance}, {"replicates", s.confirm.replicates},
                           {"budget", s.confirm.max_evaluations}, {"rounds", nlohmann::json::array()}};
  report["hold_unless_significant"] = s.confirm.hold_unless_significant;
  std::vector<EvaluationRecord> pool;  // every replicate at st.chosen so far
  for (int round = 1;; ++round) {
    report["rounds"].push_back(confirm_at(ev, st, round, pool));
    {
      const auto& last = report["rounds"].back();
      std::string line = "confirm round " + std::to_string(round) + ":";
      for (const auto& [metric, c] : last["targets"].items()) {
        if (!c.contains("rel_error")) continue;
        char buf[256];
        std::snprintf(buf, sizeof buf, " %s mean %.6g of %d runs (target %.6g), error %+.2f %% (%g %% interval %+.2f .. %+.2f %%)",
                      metric.c_str(), c["mean"].get<double>(), c["n"].get<int>(), c["target"].get<double>(),
                      100.0 * c["rel_error"].get<double>(), 100.0 * s.confirm.confidence,
                      100.0 * c["rel_error_ci"][0].get<double>(), 100.0 * c["rel_error_ci"][1].get<double>());
        line += buf;
      }
      ev.note(line);
    }
    st.rounds = round;
    store.set_stage(st.stage_prefix + "confirm", report);
    if (st.converged) { report["stop_reason"] = "converged"; break; }
    const bool hold = s.confirm.hold_unless_significant && !significant_miss(report["rounds"].back());
    const int next_cost = ((hold ? 0 : s.confirm.batch) + s.confirm.replicates) * nt;
    if (round >= s.confirm.max_rounds) { report["stop_reason"] = "round limit"; break; }
    if (ev.runs_used() - st.runs_before + next_cost > s.confirm.max_evaluations) { report["stop_reason"] = "budget of DEM runs"; break; }
    report["rounds"].back()["next"] = hold ? "hold: every target's interval holds zero; more replicates here"
                                           : "move: infill, refit and solve again";
    if (hold) {
      ev.note("confirm round " + std::to_string(round) +
              ": the miss is within the scatter; the point is kept and confirmed with more replicates");
      continue;
    }
    // Infill on the primary target's Gaussian process, conditioned on everything so far.
    if (s.confirm.batch > 0) {
      const int primary = primary_target(s);
      Eigen::MatrixXd U;
      Eigen::VectorXd y;
      gather_surrogate_data(ev, st, primary, &U, &y);
      doe::GpOptions go;
      go.seed = s.seed + static_cast<std::uint64_t>(round);
      const auto gp = doe::GaussianProcess::fit(U, y, go);
      doe::AcquisitionOptions ao;
      ao.rule = doe::AcquisitionRule::target;
      ao.target = s.targets[static_cast<std::size_t>(primary)].value;
      ao.lower = Eigen::VectorXd::Constant(U.cols(), -1.0);
      ao.upper = Eigen::VectorXd::Constant(U.cols(), 1.0);
      ao.seed = s.seed + static_cast<std::uint64_t>(round);
      ev.announce("infill round " + std::to_string(round), s.confirm.batch * nt);
      const Eigen::MatrixXd batch = doe::select_batch(gp, ao, s.confirm.batch);
      std::vector<EvalRequest> requests;
      nlohmann::json pts = nlohmann::json::array();
      for (Eigen::Index i = 0; i < batch.rows(); ++i) {
        const Eigen::VectorXd x = box_point(st, batch.row(i).transpose());
        pts.push_back(std::vector<double>(x.data(), x.data() + x.size()));
        const auto r = ev.plan("infill", full_point(st, x), 1);
        requests.insert(requests.end(), r.begin(), r.end());
      }
      ev.run(requests);
      report["rounds"].back()["infill_points"] = pts;
    }
    const Eigen::VectorXd before = st.chosen;
    fit_and_solve(ev, st, store, "solve_round_" + std::to_string(round + 1));
    // A new point starts a new pool; the same point (a solve that lands on the same corner of the
    // box) keeps its replicates.
    if (st.chosen != before) pool.clear();
  }
  store.set_stage(st.stage_prefix + "confirm", report);
  return report;
}

}  // namespace seedcal
