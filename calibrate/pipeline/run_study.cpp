#include "calibrate/pipeline/run_study.hpp"

#include <chrono>
#include <ctime>
#include <filesystem>
#include <functional>
#include <iostream>
#include <unistd.h>

#include "calibrate/pipeline/cost_estimate.hpp"
#include "calibrate/pipeline/pipeline.hpp"
#include "calibrate/pipeline/scene_check.hpp"
#include "store/atomic_file.hpp"
#include "store/errors.hpp"
#include "store/study_lock.hpp"
#include "store/version.hpp"

namespace seedcal {
namespace {

StudyStore open_store(const StudyRunOptions& o, const StudyConfig& s, const std::string& hash) {
  const std::string path = o.out_dir + "/study.h5";
  if (std::filesystem::exists(path)) {
    if (!o.resume)
      throw InputError(path + ": a study is already stored here; continue it with --resume, or choose another --out");
    StudyStore store = StudyStore::open(path);
    // A store from a build that named the study's files as the command line spelt them.
    if (store.header().config_hash != hash && store.header().config_hash == study_fingerprint_as_spelt(s))
      store.set_config_hash(hash);
    if (store.header().config_hash != hash)
      throw InputError(path + ": this study directory was made from a different study (fingerprint " +
                       store.header().config_hash + ", now " + hash + "): the study file " + o.study_file +
                       ", its overrides or a scene or clump file it names changed since. Resume with the "
                       "unchanged files, or start the changed study in another --out directory");
    return store;
  }
  StudyHeader h{hash, s.text, version_string(), utc_now()};
  return StudyStore::create(path, h);
}

// A digest of the stages for summary.json (the full designs and fits are in study.h5, /stages).
nlohmann::json stage_digest(const nlohmann::json& stages) {
  nlohmann::json digest = nlohmann::json::object();
  if (stages.contains("screen")) {
    nlohmann::json sc = {{"kept", stages["screen"]["kept"]}, {"effects", nlohmann::json::object()}};
    for (const auto& t : stages["screen"]["targets"]) {
      sc["effects"][t.value("name", "")] = t.value("effects", nlohmann::json::array());
      if (t.contains("run_noise_sd"))
        sc["run_noise_sd"][t.value("name", "")] = {{"estimate", t["run_noise_sd"]}, {"lower95", t["run_noise_sd_lower95"]}};
    }
    digest["screen"] = sc;
  }
  if (stages.contains("ascent"))
    digest["ascent"] = {{"result", stages["ascent"].value("stop_reason", stages["ascent"].value("skipped", std::string()))},
                        {"points", stages["ascent"]["points"].size()},
                        {"surrogate_box", stages["ascent"]["surrogate_box"]}};
  for (int round = 100; round >= 1; --round) {
    const std::string key = "solve_round_" + std::to_string(round);
    if (!stages.contains(key)) continue;
    nlohmann::json fits = nlohmann::json::object();
    for (const auto& t : stages[key]["targets"]) {
      nlohmann::json f = {{"chosen", t.value("chosen", std::string())}, {"points", t.value("points", 0)}};
      if (t.contains("quadratic") && t["quadratic"].contains("loo_rmse")) f["quadratic_loo_rmse"] = t["quadratic"]["loo_rmse"];
      if (t.contains("gp") && t["gp"].contains("loo_rmse")) f["gp_loo_rmse"] = t["gp"]["loo_rmse"];
      if (t.contains("gp") && t["gp"].contains("noise_sd")) f["gp_noise_sd"] = t["gp"]["noise_sd"];
      if (t.contains("gp") && t["gp"].contains("noise_floor_sd")) f["gp_noise_floor_sd"] = t["gp"]["noise_floor_sd"];
      fits[t.value("name", "")] = f;
    }
    digest["surrogate"] = {{"round", round}, {"fits", fits}};
    break;
  }
  if (stages.contains("confirm")) {
    digest["confirm_stop_reason"] = stages["confirm"].value("stop_reason", std::string("running"));
    // Per round: where, how many replicates the pooled result rests on, and what came next.
    nlohmann::json rounds = nlohmann::json::array();
    const nlohmann::json& confirm = stages["confirm"];
    if (confirm.contains("rounds")) {
      for (const nlohmann::json& r : confirm["rounds"]) {
        nlohmann::json d = nlohmann::json::object();
        for (const char* k : {"round", "point", "runs_at_point", "next"})
          if (r.contains(k)) d[k] = r[k];
        d["infill_points"] = r.contains("infill_points") ? r["infill_points"].size() : 0;
        if (r.contains("targets")) {
          for (const auto& item : r["targets"].items()) {
            nlohmann::json m = nlohmann::json::object();
            for (const char* k : {"n", "mean", "sd", "rel_error", "rel_error_ci", "significant_miss"})
              if (item.value().contains(k)) m[k] = item.value()[k];
            d["targets"][item.key()] = m;
          }
        }
        rounds.push_back(d);
      }
    }
    digest["confirm_rounds"] = rounds;
  }
  return digest;
}

StudySummary summary_of(const StudyConfig& s, const PipelineState& st, const std::vector<PipelineState>& others,
                        const StudyEvaluator& ev, const StudyStore& store, const std::string& stage_reached,
                        const std::string& hash, const std::vector<std::string>& warnings) {
  StudySummary out;
  out.warnings = warnings;
  out.schema_version = kStudyStoreSchemaVersion;  // the study directory's layout (docs/store.md)
  out.study = s.name;
  out.stage_reached = stage_reached;
  if (st.chosen.size() == static_cast<Eigen::Index>(s.parameters.size())) {
    for (std::size_t p = 0; p < s.parameters.size(); ++p) {
      (st.is_kept(static_cast<int>(p)) ? out.calibrated : out.held_at_nominal)[s.parameters[p].path] =
          st.chosen(static_cast<Eigen::Index>(p));
    }
  }
  for (const auto& t : s.targets) out.targets[t.metric] = t.value;
  out.confirmed = st.confirmed;
  out.converged = st.converged;
  out.confirmation_rounds = st.rounds;
  // Calibration runs (stages 1-5: what the classical workflow's count compares with); the
  // verification runs come on top.
  out.evaluations = st.calibration_runs >= 0 ? st.calibration_runs : ev.runs_used();
  out.evaluations_total = ev.runs_used();
  out.evaluations_from_store = ev.runs_reused();
  // PB + ~5 path points + 13-run CCD, x3 replicates, + 3 confirmations; every point runs every
  // target's test (a joint study of two tests runs both at each point).
  out.classical_workflow_evaluations = (3 * (s.screen.runs + 5 + 13) + 3) * static_cast<int>(s.targets.size());
  if (!st.solution.is_null()) out.solution_set = st.solution;
  // The posterior (posterior_stage.cpp): 95 % credible intervals and identification, with reasons.
  const std::string posterior_report = "the posterior stage's report";
  if (st.posterior.is_object()) {
    posterior_identification(st.posterior, posterior_report, &out.calibrated_interval, &out.identified);
    out.posterior = st.posterior;
    out.posterior.erase("region_grid");  // in study.h5 (/stages/posterior) and the report
  }
  if (st.curve.is_object()) out.curve = st.curve;
  // [verify] calibrate_each_model: every model's own calibration, the first's as above.
  if (s.verify.calibrate_each_model && s.models.size() > 1) {
    for (std::size_t m = 0; m < s.models.size(); ++m) {
      const PipelineState& sm = m == 0 ? st : others[m];
      ModelCalibration e;
      e.model = s.models[m].name;
      e.stage_prefix = sm.stage_prefix;
      if (sm.chosen.size() == static_cast<Eigen::Index>(s.parameters.size())) {
        e.calibrated_yet = true;
        for (const int p : sm.kept) e.calibrated[s.parameters[static_cast<std::size_t>(p)].path] = sm.chosen(p);
        e.converged = sm.converged;
        e.confirmed = sm.confirmed;
        e.evaluations = sm.calibration_runs;
      }
      if (sm.posterior.is_object()) {
        posterior_identification(sm.posterior, posterior_report, &e.calibrated_interval.emplace(), &e.identified.emplace());
      }
      if (sm.curve.is_object() && sm.curve.contains("picked")) e.curve_picked = sm.curve["picked"];
      out.calibration_per_model.push_back(std::move(e));
    }
  }
  out.tolerance = s.confirm.tolerance;
  out.verification = st.verification;
  out.model_selection = st.selection;
  out.stages = stage_digest(store.stages());
  const double cpu = ev.calibration_cpu_seconds(), cpu_verify = ev.verification_cpu_seconds();
  out.cpu_seconds = cpu + cpu_verify;
  out.calibration_cpu_seconds = cpu;
  out.verification_cpu_seconds = cpu_verify;
  if (store.stages().contains("sessions"))
    for (const auto& x : store.stages()["sessions"]) out.wall_seconds += x.value("wall_seconds", 0.0);
  out.provenance = {version_string(), s.file, hash, s.text, s.seed};
  return out;
}

// The report (reports/, docs/reports.md), when the caller renders one: study.h5 and summary.json
// as report.html, report.md and report/*.csv|svg. A report that cannot be written is logged and
// does not fail the study (`seedcal report DIR` renders it again).
void write_study_report(const StudyRunOptions& o, Progress& progress) {
  if (!o.render_report) return;
  try {
    o.render_report(o.out_dir);
    progress.log("report: " + o.out_dir + "/report.html");
  } catch (const std::exception& e) {
    progress.log(std::string("report not written (seedcal report ") + o.out_dir + " renders it again): " + e.what());
  }
}

// The estimate as the summary's sessions record it.
nlohmann::json cost_json(const StudyCostEstimate& e) {
  nlohmann::json stages = nlohmann::json::object();
  for (const StageRuns& r : e.stages) stages[r.stage] = {{"runs", r.runs}, {"at_most", r.at_most}, {"cpu_s", r.cpu_s}};
  nlohmann::json scenes = nlohmann::json::array();
  for (const SceneCost& c : e.scenes)
    scenes.push_back({{"test", c.test}, {"model", c.model}, {"kind", c.kind}, {"seeds", c.plan.seeds},
                      {"spheres", c.plan.spheres}, {"simulated_s", c.plan.simulated_s()}, {"dt_s", c.plan.dt_s},
                      {"cpu_s_per_sphere_step", c.cpu_s_per_sphere_step}, {"cpu_s_per_run", c.cpu_s}});
  for (std::size_t k = 0; k < e.scenes.size(); ++k) {
    if (!e.scenes[k].refused.empty()) scenes[k]["refused"] = e.scenes[k].refused;
    if (e.scenes[k].cpu_s_per_sphere_step_loaded > 0.0) {
      scenes[k]["cpu_s_per_sphere_step_loaded"] = e.scenes[k].cpu_s_per_sphere_step_loaded;
      scenes[k]["confining_stress_pa"] = e.scenes[k].confining_stress_pa;
    }
  }
  return {{"runs", e.runs}, {"runs_at_most", e.runs_at_most}, {"cpu_s", e.cpu_s}, {"cpu_s_at_most", e.cpu_s_at_most},
          {"probe_cpu_s", e.probe_cpu_s}, {"stages", stages}, {"scenes", scenes}};
}

// Stages 1-5, the posterior and the pick along the solution curve, for the model `st` calibrates;
// `checkpoint` writes the summary after each.
void calibrate_stages(StudyEvaluator& ev, PipelineState& st, StudyStore& store, Progress& progress, const std::string& out_dir,
                      const std::function<nlohmann::json(const std::string&)>& checkpoint) {
  const StudyConfig& s = ev.study();
  const std::string who = st.model == 0 ? "" : " [" + s.models[static_cast<std::size_t>(st.model)].name + "]";
  const auto log_identified = [&](const std::string& what, const nlohmann::json& post) {
    const nlohmann::json identified = post.value("identified", nlohmann::json::object());
    std::string line;
    for (const auto& [path, ok] : identified.items())
      line += (line.empty() ? "" : ", ") + path + (ok.get<bool>() ? " identified" : " not identified");
    if (!line.empty()) progress.log(what + who + ": " + line);
  };
  const int targets = static_cast<int>(s.targets.size());
  progress.stage("screen" + who, s.screen.runs * s.screen.replicates * targets);
  const auto screen = run_screening(ev, st, store);
  std::string kept;
  for (const auto& k : screen["kept"]) kept += (kept.empty() ? "" : ", ") + k.get<std::string>();
  progress.log("screen" + who + ": kept " + kept);
  checkpoint("screen");

  progress.stage("ascent" + who, s.ascent.max_steps * s.screen.replicates * targets);
  const auto ascent = run_ascent(ev, st, store);
  progress.log("ascent" + who + ": " + ascent.value("stop_reason", ascent.value("skipped", std::string())));
  checkpoint("ascent");

  const auto design_runs = static_cast<int>(surrogate_design(s, static_cast<int>(st.kept.size())).rows());
  progress.stage("surrogate" + who, design_runs * s.surrogate.replicates * targets);
  run_surrogate_design(ev, st, store);
  const auto solved = fit_and_solve(ev, st, store, "solve_round_1");
  progress.log("surrogate" + who + ": " + st.surrogate_kind + ", chosen " + solved["solution"]["chosen"].dump());
  checkpoint("solve");

  const auto confirm = run_confirmation(ev, st, store);
  st.calibration_runs = ev.runs_used() - st.runs_before;
  progress.log("confirm" + who + ": " + confirm.value("stop_reason", std::string()) + ", " +
               std::to_string(st.calibration_runs) + " DEM runs");
  log_identified("posterior", run_posterior(ev, st, store));
  checkpoint("confirm");

  // One target leaving two parameters on a curve: a verification test picks the point along it,
  // and the posterior is taken again with it.
  if (s.checks.empty()) return;
  const auto curve = run_curve_pick(ev, st, store, out_dir);
  if (curve.contains("skipped")) {
    progress.log("curve" + who + ": not run: " + curve["skipped"].get<std::string>());
  } else {
    progress.log("curve" + who + ": " + curve["test"].get<std::string>() +
                 (curve.value("mode", std::string()) == "region" ? " at the box's corners" : " along the solution curve") + ", picked " +
                 curve["picked"].dump() + (curve.contains("note") ? " (" + curve["note"].get<std::string>() + ")" : ""));
    log_identified("posterior with " + curve["test"].get<std::string>(), run_posterior(ev, st, store));
    const nlohmann::json moved = keep_pick_in_posterior(s, st, store);
    if (!moved.is_null()) {
      progress.log("curve" + who + ": " + moved["reason"].get<std::string>() + ": " + moved["picked"].dump());
      refresh_edge_flags(s, st, store);
    }
  }
  checkpoint("curve");
}

}  // namespace

nlohmann::json run_study(const StudyRunOptions& o, const ExecutorFactory& make_executor) {
  const StudyConfig s = read_study(o.study_file, o.sets);
  // Bad input is refused before any run (exit 2); warnings are said now and logged below.
  const std::vector<std::string> warnings = check_study_scenes(s);
  for (const std::string& w : warnings) std::cerr << "seedcal: warning: " << w << "\n";
  const std::string hash = study_fingerprint(s);
  const StudyCostEstimate cost = estimate_study_cost(s, o.threads);
  if (o.dry_run) {
    for (const std::string& line : describe_cost(cost, o.jobs)) std::cout << line << "\n";
    return cost_json(cost);
  }
  const std::unique_ptr<Executor> executor = make_executor(hash);
  std::filesystem::create_directories(o.out_dir);
  // One calibrate at a time on a study directory (store/study_lock.hpp): taken before the store is
  // read, held until the summary is written.
  std::vector<std::string> lock_warnings;
  const StudyLock lock(o.out_dir, o.force_unlock, lock_warnings);
  for (const std::string& w : lock_warnings) std::cerr << "seedcal: warning: " << w << "\n";
  StudyStore store = open_store(o, s, hash);
  Progress progress(o.out_dir + "/calibrate.log", o.progress_on_terminal && ::isatty(STDERR_FILENO), executor->slots());
  const auto t0 = std::chrono::steady_clock::now();
  nlohmann::json sessions = store.stages().value("sessions", nlohmann::json::array());
  const std::size_t session = sessions.size();
  sessions.push_back({{"started_utc", utc_now()}, {"wall_seconds", 0.0}, {"executor", executor->describe()},
                      {"threads_per_simulation", o.threads}, {"seedcal_version", version_string()}});
  store.set_stage("sessions", sessions);
  progress.log("study " + s.name + " (" + s.file + "), fingerprint " + hash + ", " + executor->describe() +
               (store.evaluations().empty() ? "" : ", resuming with " + std::to_string(store.evaluations().size()) + " stored runs"));

  for (const std::string& w : warnings) progress.log("warning: " + w);
  // What the whole study costs (runs already in the store are not redone).
  for (const std::string& line : describe_cost(cost, executor->slots())) {
    if (!o.progress_on_terminal || !::isatty(STDERR_FILENO)) std::cerr << "seedcal: " << line << "\n";
    progress.log(line);
  }
  sessions[session]["estimate"] = cost_json(cost);
  store.set_stage("sessions", sessions);
  StudyEvaluator ev(s, store, *executor, progress);
  if (o.trajectories.any()) ev.record_trajectories(o.trajectories, o.out_dir);
  PipelineState st;
  std::vector<PipelineState> others(s.models.size());  // [verify] calibrate_each_model: models 1 ..
  auto checkpoint = [&](const std::string& stage) {
    sessions[session]["wall_seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    store.set_stage("sessions", sessions);
    const nlohmann::json j = to_json(summary_of(s, st, others, ev, store, stage, hash, warnings));
    write_json_atomic(o.out_dir + "/summary.json", j);
    return j;
  };
  calibrate_stages(ev, st, store, progress, o.out_dir, checkpoint);
  // [verify] calibrate_each_model: every other model gets the same stages under its own overrides
  // (its stages in the store under "model:NAME/"), then is verified at its own point.
  std::vector<const PipelineState*> calibrated;
  if (s.verify.calibrate_each_model && s.models.size() > 1) {
    calibrated.push_back(&st);
    for (std::size_t m = 1; m < s.models.size(); ++m) {
      PipelineState& sm = others[m];
      sm.model = static_cast<int>(m);
      sm.stage_prefix = "model:" + s.models[m].name + "/";
      sm.runs_before = ev.runs_used();
      ev.set_calibration_model(sm.model);
      progress.log("calibrating model \"" + s.models[m].name + "\"");
      calibrate_stages(ev, sm, store, progress, o.out_dir, checkpoint);
      calibrated.push_back(&sm);
    }
    ev.set_calibration_model(0);
  }

  // Verification and model selection run only when the study asks for them (tests or models).
  if (!s.checks.empty() || s.models.size() > 1) {
    const auto selection = run_verification(ev, st, store, o.out_dir, [&](int done) {
      progress.log("verify: " + std::to_string(done) + " of " + std::to_string(s.models.size()) +
                   " models verified, provisional choice " + st.selection["chosen"].dump());
      checkpoint("verify");
      write_study_report(o, progress);
    }, calibrated);
    progress.log("verify: chosen model " + selection["chosen"].dump() + ", " + std::to_string(ev.runs_used()) +
                 " DEM runs in all");
  }
  const nlohmann::json summary = checkpoint("done");
  write_study_report(o, progress);
  return summary;
}

}  // namespace seedcal
