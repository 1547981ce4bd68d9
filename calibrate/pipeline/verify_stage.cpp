// Stages 6 and 7 (DESIGN.md, "Calibration pipeline"): verification and model selection.
//
// Verification: for every clump model of the study (its overrides applied to every scene) and
// every test (the calibration targets, then the [[verify.test]] entries), `verify.replicates` (or
// the test's own `replicates`) fresh DEM runs (unused seeds) at the calibrated values. Per test: mean, sample sd, relative error
// e = mean / experiment - 1, and within_sd = |mean - experiment| <= experimental sd when the
// experiment gives one. A test without an experimental value is reported as simulation only. The
// first replicate of each test writes its CSV and picture under DIR/scenes/MODEL/TEST/ (and its
// trajectory, when the study records the verification's: study_trajectories.hpp).
//
// Selection, following the paper's section 3 (the models are compared on every test, with their
// CPU time): per model
//   error = mean of |e| over the tests with an experimental value, with its standard error from
//           the tests' replicate scatter (a test run once takes its sd pooled over the models
//           that ran it more often),
//   cost  = CPU seconds of one run of every test (each test's mean over its replicates, summed).
// The Pareto front holds the models no other model beats on both. The choice (model_choice.hpp):
// the cheapest model whose error cannot be told apart from the lowest, within
// `verify.error_margin` plus the scatter; the ties and the replicates it would take to separate
// the leaders are reported. Also reported, for information: accuracy per CPU second =
// (1 - error) / cost.
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <set>

#include <gsl/gsl_statistics_double.h>

#include "calibrate/pipeline/model_choice.hpp"
#include "calibrate/pipeline/pipeline.hpp"

namespace seedcal {
namespace {

nlohmann::json null_if_nan(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

// One test of one model from its replicate records.
nlohmann::json summarise_test(const StudyConfig& s, int scene, const std::vector<const EvaluationRecord*>& runs,
                              double* cpu_per_run) {
  const StudyTarget& t = s.scene_of(scene);
  const bool is_target = scene < static_cast<int>(s.targets.size());
  std::vector<double> v;
  std::vector<std::uint64_t> seeds;
  double cpu = 0.0;
  int ran = 0;
  // A drum whose shell slid under a bed at rest (scenes/drum.hpp): the frames' angles are held by
  // the wall friction, which the report says beside the result.
  int drum_frames = 0, slipping = 0;
  bool drum = false;
  nlohmann::json failures = nlohmann::json::array(), skipped = nlohmann::json::array();
  for (const auto* r : runs) {
    if (r->status == "skipped") {  // not run (StudyEvaluator::run): no result, no cost
      skipped.push_back({{"seed", r->seed}, {"reason", r->message}});
      continue;
    }
    cpu += r->cpu_seconds;
    ++ran;
    if (r->metrics.contains("slipping_frames")) {
      drum = true;
      slipping += r->metrics["slipping_frames"].get<int>();
      drum_frames += static_cast<int>(r->metrics.value("frames", nlohmann::json::array()).size());
    }
    const double x = record_metric(s, *r);
    if (std::isfinite(x)) {
      v.push_back(x);
      seeds.push_back(r->seed);
    } else {
      failures.push_back({{"seed", r->seed}, {"status", r->status}, {"message", r->message}});
    }
  }
  *cpu_per_run = ran == 0 ? 0.0 : cpu / static_cast<double>(ran);
  nlohmann::json j = {{"test", t.name}, {"label", t.name}, {"metric", t.metric}, {"role", is_target ? "target" : "verification"},
                      {"n", v.size()}, {"samples", v}, {"seeds", seeds}, {"cpu_seconds", *cpu_per_run}};
  if (!failures.empty()) j["failures"] = failures;
  if (!skipped.empty()) j["skipped"] = skipped;
  if (drum) {
    j["drum_frames"] = drum_frames;
    j["drum_slipping_frames"] = slipping;
  }
  const double mean = v.empty() ? std::numeric_limits<double>::quiet_NaN() : gsl_stats_mean(v.data(), 1, v.size());
  const double sd = v.size() < 2 ? std::numeric_limits<double>::quiet_NaN() : gsl_stats_sd_m(v.data(), 1, v.size(), mean);
  j["mean"] = null_if_nan(mean);
  j["sd"] = null_if_nan(sd);
  if (t.has_value) {
    j["experimental_mean"] = t.value;
    j["experimental_sd"] = t.sd > 0.0 ? nlohmann::json(t.sd) : nlohmann::json(nullptr);
    j["rel_error"] = null_if_nan(mean / t.value - 1.0);
    j["within_sd"] = t.sd > 0.0 && std::isfinite(mean) ? nlohmann::json(std::fabs(mean - t.value) <= t.sd) : nlohmann::json(nullptr);
  } else {
    j["experimental_mean"] = nullptr;
    j["experimental_sd"] = nullptr;
    j["rel_error"] = nullptr;
    j["within_sd"] = nullptr;
    j["note"] = "simulation only: the study gives no experimental value";
  }
  return j;
}

// Rows, Pareto front and choice over the first `done` models, whose records are all in
// `records`; sets st.verification and st.selection and records the stage in the store. With
// done < models the selection is marked partial: the choice is among the verified models only.
nlohmann::json select_models(const StudyConfig& s, PipelineState& st, StudyStore& store,
                             const std::vector<EvaluationRecord>& records,
                             const std::vector<std::vector<std::size_t>>& first, int done,
                             const std::function<int(int)>& reps_of, const std::function<int(int, int)>& runs_of,
                             const std::function<const PipelineState&(int)>& state_of, bool each_model) {
  const int models = static_cast<int>(s.models.size());
  const int scenes = s.scene_count();
  nlohmann::json rows = nlohmann::json::array();
  std::vector<double> error(static_cast<std::size_t>(done)), cost(static_cast<std::size_t>(done));
  for (int m = 0; m < done; ++m) {
    nlohmann::json tests = nlohmann::json::array();
    double sum_abs = 0.0, cpu = 0.0, spheres = 0.0;
    int with_value = 0, within = 0, with_sd = 0;
    bool complete = true;
    for (int t = 0; t < scenes; ++t) {
      std::vector<const EvaluationRecord*> runs;
      for (int rep = 0; rep < runs_of(m, t); ++rep) {
        const auto& r = records[first[static_cast<std::size_t>(m)][static_cast<std::size_t>(t)] + static_cast<std::size_t>(rep)];
        runs.push_back(&r);
        if (r.status == "ok" && r.metrics.contains("bodies") && r.metrics.contains("spheres") &&
            r.metrics["bodies"].get<double>() > 0)
          spheres = r.metrics["spheres"].get<double>() / r.metrics["bodies"].get<double>();
      }
      double cpu_t = 0.0;
      // The test run along the solution curve: its runs there are its verification under the
      // first model (curve_stage.cpp).
      const bool from_curve = runs_of(m, t) == 0 && t == state_of(m).curve_scene;
      nlohmann::json j = from_curve ? state_of(m).curve_verification : summarise_test(s, t, runs, &cpu_t);
      if (from_curve) cpu_t = j["cpu_seconds"].get<double>();
      cpu += cpu_t;
      if (!j["rel_error"].is_null()) {
        sum_abs += std::fabs(j["rel_error"].get<double>());
        ++with_value;
      } else if (s.scene_of(t).has_value) {
        complete = false;  // the experiment has a value but every run failed
      }
      if (!j["within_sd"].is_null()) {
        ++with_sd;
        within += j["within_sd"].get<bool>() ? 1 : 0;
      }
      tests.push_back(j);
    }
    const double err = with_value > 0 && complete ? sum_abs / with_value : std::numeric_limits<double>::quiet_NaN();
    error[static_cast<std::size_t>(m)] = err;
    cost[static_cast<std::size_t>(m)] = cpu;
    rows.push_back({{"model", s.models[static_cast<std::size_t>(m)].name},
                    {"set", s.models[static_cast<std::size_t>(m)].sets},
                    {"spheres", spheres > 0 ? nlohmann::json(std::lround(spheres)) : nlohmann::json(nullptr)},
                    {"tests", tests},
                    {"mean_abs_rel_error", null_if_nan(err)},
                    {"tests_with_experiment", with_value},
                    {"within_sd", within},
                    {"tests_with_sd", with_sd},
                    {"cpu_seconds", cpu},
                    {"accuracy_per_cpu_second", std::isfinite(err) && cpu > 0 ? nlohmann::json((1.0 - err) / cpu) : nlohmann::json(nullptr)}});
  }
  // Each test's scatter: its sd over the replicates, or for a model that ran it once the sd pooled
  // over the models that ran it more often.
  std::vector<double> pooled_sd(static_cast<std::size_t>(scenes), std::numeric_limits<double>::quiet_NaN());
  for (int t = 0; t < scenes; ++t) {
    double ss = 0.0;
    int df = 0;
    for (int m = 0; m < done; ++m) {
      const auto& j = rows[static_cast<std::size_t>(m)]["tests"][static_cast<std::size_t>(t)];
      const int n = j["n"].get<int>();
      const int sd_df = j.value("sd_df", n - 1);
      if (sd_df >= 1 && !j["sd"].is_null()) {
        ss += sd_df * std::pow(j["sd"].get<double>(), 2);
        df += sd_df;
      }
    }
    if (df > 0) pooled_sd[static_cast<std::size_t>(t)] = std::sqrt(ss / df);
  }
  // A test that every model ran once has no scatter to count: its share of the error's standard
  // error is left out (the comparison then understates the scatter), and the selection says so.
  std::vector<ModelScore> scores(static_cast<std::size_t>(done));
  std::set<std::string> no_scatter;
  for (int m = 0; m < done; ++m) {
    double var = 0.0;
    int with_value = 0, with_scatter = 0;
    for (int t = 0; t < scenes; ++t) {
      const auto& j = rows[static_cast<std::size_t>(m)]["tests"][static_cast<std::size_t>(t)];
      if (j["rel_error"].is_null()) continue;
      ++with_value;
      const int n = j["n"].get<int>();
      const double sd = n >= 2 && !j["sd"].is_null() ? j["sd"].get<double>() : pooled_sd[static_cast<std::size_t>(t)];
      if (!std::isfinite(sd)) {
        no_scatter.insert(s.scene_of(t).name);
        continue;
      }
      // The mean's standard error: sd / sqrt(n), or the curve line's own at the point.
      const double se = j.contains("mean_se") ? j["mean_se"].get<double>() : sd / std::sqrt(static_cast<double>(n));
      var += std::pow(se / std::fabs(s.scene_of(t).value), 2);
      ++with_scatter;
    }
    const double se = with_scatter > 0 ? std::sqrt(var) / with_value : std::numeric_limits<double>::quiet_NaN();
    scores[static_cast<std::size_t>(m)] = {error[static_cast<std::size_t>(m)], se, cost[static_cast<std::size_t>(m)]};
    rows[static_cast<std::size_t>(m)]["mean_abs_rel_error_se"] = null_if_nan(se);
  }
  const ModelChoice choice = choose_model(scores, s.verify.error_margin, s.verify.cost_margin);
  const int chosen = choice.chosen;
  const double best = choice.best >= 0 ? error[static_cast<std::size_t>(choice.best)] : 0.0;
  nlohmann::json ties = nlohmann::json::array();
  for (int m = 0; m < done; ++m) {
    const auto i = static_cast<std::size_t>(m);
    bool dominated = !std::isfinite(error[i]);
    for (int k = 0; k < done && !dominated; ++k) {
      const auto j = static_cast<std::size_t>(k);
      if (k == m || !std::isfinite(error[j])) continue;
      dominated = error[j] <= error[i] && cost[j] <= cost[i] && (error[j] < error[i] || cost[j] < cost[i]);
    }
    rows[i]["pareto"] = !dominated;
    rows[i]["tied_with_best"] = static_cast<bool>(choice.tied[i]);
    if (choice.tied[i]) ties.push_back(s.models[i].name);
  }
  char rule[520];
  std::snprintf(rule, sizeof rule,
                "error = mean |relative error| over the tests with an experimental value, with its standard error from "
                "the replicates; cost = CPU seconds of one run of every test; chosen: the cheapest model whose error "
                "exceeds the lowest (%.4g) by no more than %.3g plus 1.645 standard errors of the difference, "
                "when it saves at least %.3g of the most accurate model's cost (else the most accurate)",
                best, s.verify.error_margin, s.verify.cost_margin);
  nlohmann::json selection = {{"rule", rule}, {"error_margin", s.verify.error_margin}, {"cost_margin", s.verify.cost_margin}, {"models", rows},
                              {"chosen", chosen >= 0 ? nlohmann::json(s.models[static_cast<std::size_t>(chosen)].name)
                                                     : nlohmann::json(nullptr)},
                              {"most_accurate", choice.best >= 0 ? nlohmann::json(s.models[static_cast<std::size_t>(choice.best)].name)
                                                                 : nlohmann::json(nullptr)},
                              {"tied", ties}, {"comparison", choice.comparison},
                              {"models_verified", done}, {"models_planned", models}, {"partial", done < models}};
  if (!no_scatter.empty()) {
    std::string names;
    for (const auto& n : no_scatter) names += (names.empty() ? "" : ", ") + n;
    selection["scatter_note"] = "run once by every model, so their scatter is not counted in the comparison: " + names;
  }
  if (chosen >= 0 && chosen != choice.best) {
    // The replicates per test it would take to tell the chosen model from the most accurate one.
    if (choice.replicates_factor > 0.0) {
      nlohmann::json reps = nlohmann::json::object();
      for (int t = 0; t < scenes; ++t)
        reps[s.scene_of(t).name] = static_cast<int>(std::ceil(reps_of(t) * choice.replicates_factor));
      selection["replicates_to_separate"] = reps;
    } else {
      selection["replicates_to_separate"] = nullptr;
      selection["replicates_note"] = "their errors differ by less than the margin: no number of replicates separates them";
    }
  }
  if (done < models) {
    std::string waiting;
    for (int m = done; m < models; ++m) waiting += (m > done ? ", " : "") + s.models[static_cast<std::size_t>(m)].name;
    selection["note"] = "partial: " + std::to_string(done) + " of " + std::to_string(models) +
                        " models verified (not yet: " + waiting +
                        "); the choice is among the verified models only. An interrupted study continues with --resume";
  } else if (chosen < 0) {
    selection["note"] = "no model has an error on every test with an experimental value";
  }
  const auto point_of = [&](int m) {
    nlohmann::json at = nlohmann::json::object();
    for (std::size_t p = 0; p < s.parameters.size(); ++p) at[s.parameters[p].path] = state_of(m).chosen(static_cast<Eigen::Index>(p));
    return at;
  };
  const int shown = chosen >= 0 ? chosen : 0;
  const nlohmann::json at = point_of(shown);
  selection["verified_at"] = at;
  std::string note;
  if (each_model) {
    nlohmann::json per = nlohmann::json::object();
    for (int m = 0; m < models; ++m) per[s.models[static_cast<std::size_t>(m)].name] = point_of(m);
    selection["verified_at_per_model"] = per;
    note = "each model is verified at its own calibrated values ([verify] calibrate_each_model)";
  } else {
    note = "every model is verified at the values calibrated with the first model (\"" + s.models.front().name +
           "\"); a model that needs other values shows it as a larger error";
  }
  for (int m = 0; m < models; ++m)
    if (state_of(m).curve_scene >= 0 && (each_model || m == 0))
      note += "; \"" + s.scene_of(state_of(m).curve_scene).name + "\" of \"" + s.models[static_cast<std::size_t>(m)].name +
              "\" is read from its runs along the solution curve";
  selection["verified_at_note"] = note;
  st.verification = {{"model", s.models[static_cast<std::size_t>(shown)].name}, {"replicates", s.verify.replicates}, {"point", at},
                     {"tests", rows[static_cast<std::size_t>(shown)]["tests"]}};
  st.selection = selection;
  store.set_stage("verify", {{"point", at}, {"replicates", s.verify.replicates}, {"selection", selection}});
  return selection;
}

}  // namespace

nlohmann::json run_verification(StudyEvaluator& ev, PipelineState& st, StudyStore& store, const std::string& out_dir,
                                 const std::function<void(int models_done)>& on_model_done,
                                 const std::vector<const PipelineState*>& calibrated) {
  const StudyConfig& s = ev.study();
  const int models = static_cast<int>(s.models.size());
  const int scenes = s.scene_count();
  const std::function<int(int)> reps_of = [&](int t) {
    const int r = s.scene_of(t).replicates;
    return t >= static_cast<int>(s.targets.size()) && r > 0 ? r : s.verify.replicates;
  };
  // With calibrate_each_model each model has its own calibration (its point and curve), else
  // every model is verified at the first model's.
  const bool each_model = !calibrated.empty();
  const std::function<const PipelineState&(int)> state_of = [&](int m) -> const PipelineState& {
    return each_model && m > 0 ? *calibrated.at(static_cast<std::size_t>(m)) : st;
  };
  // The test run along a model's solution curve has that model's runs already (curve_stage.cpp).
  const std::function<int(int, int)> runs_of = [&](int m, int t) {
    return (m == 0 || each_model) && t == state_of(m).curve_scene ? 0 : reps_of(t);
  };
  int planned = 0;
  for (int m = 0; m < models; ++m)
    for (int t = 0; t < scenes; ++t) planned += runs_of(m, t);
  ev.announce("verify", planned);
  // Every request is planned in model order and run as one batch (a long run of one model
  // overlaps the next model's runs on the --jobs slots). As soon as every run of the first k
  // models is in, the selection over those k models is made and `on_model_done(k)` writes it:
  // a selection of hours at paper fidelity shows each finished model while the rest run.
  std::vector<EvalRequest> requests;
  std::vector<int> model_of;
  std::vector<std::vector<std::size_t>> first(static_cast<std::size_t>(models), std::vector<std::size_t>(static_cast<std::size_t>(scenes)));
  for (int m = 0; m < models; ++m) {
    for (int t = 0; t < scenes; ++t) {
      first[static_cast<std::size_t>(m)][static_cast<std::size_t>(t)] = requests.size();
      for (int rep = 0; rep < runs_of(m, t); ++rep) {
        const std::string dir = rep == 0 ? out_dir + "/scenes/" + path_slug(s.models[static_cast<std::size_t>(m)].name) + "/" +
                                               path_slug(s.scene_of(t).name)
                                         : std::string();
        requests.push_back(ev.plan_one("verify", state_of(m).chosen, t, m, dir));
        model_of.push_back(m);
      }
    }
  }
  std::vector<EvaluationRecord> arrived(requests.size());
  std::vector<char> in(requests.size(), 0);
  std::vector<int> missing(static_cast<std::size_t>(models), 0);
  for (const int m : model_of) ++missing[static_cast<std::size_t>(m)];
  // A model whose every run of a test with an experimental value failed has no error, so the rule
  // cannot choose it (select_models): its runs not yet started are skipped, not run. At paper
  // fidelity that can be hours of simulations whose results could not change the choice.
  const auto unneeded = [&](std::size_t i) -> std::string {
    const int m = model_of[i];
    for (int t = 0; t < scenes; ++t) {
      if (!s.scene_of(t).has_value || runs_of(m, t) == 0) continue;
      const std::size_t f = first[static_cast<std::size_t>(m)][static_cast<std::size_t>(t)];
      std::string why;
      bool failed_all = true;
      for (int rep = 0; rep < runs_of(m, t) && failed_all; ++rep) {
        const std::size_t k = f + static_cast<std::size_t>(rep);
        const bool failed = in[k] && arrived[k].status != "skipped" && !std::isfinite(record_metric(s, arrived[k]));
        failed_all = failed;
        if (failed && why.find(arrived[k].status) == std::string::npos)
          why += (why.empty() ? "" : ", ") + arrived[k].status;
      }
      if (failed_all)
        return "model \"" + s.models[static_cast<std::size_t>(m)].name + "\" cannot be chosen: every run of \"" +
               s.scene_of(t).name + "\" failed (" + why + "; the test's failures say why)";
    }
    return "";
  };
  int complete = 0;  // models 0 .. complete-1 have every record
  const auto records = ev.run(requests, [&](std::size_t i, const EvaluationRecord& r) {
    arrived[i] = r;
    in[i] = 1;
    --missing[static_cast<std::size_t>(model_of[i])];
    const int before = complete;
    while (complete < models && missing[static_cast<std::size_t>(complete)] == 0) ++complete;
    if (complete > before && complete < models) {
      select_models(s, st, store, arrived, first, complete, reps_of, runs_of, state_of, each_model);
      if (on_model_done) on_model_done(complete);
    }
  }, unneeded);
  return select_models(s, st, store, records, first, models, reps_of, runs_of, state_of, each_model);
}

}  // namespace seedcal
