#include "calibrate/pipeline/cost_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "calibrate/pipeline/evaluation.hpp"
#include "calibrate/pipeline/pipeline.hpp"
#include "calibrate/pipeline/progress.hpp"
#include "calibrate/scenes/scene_file.hpp"
#include "store/errors.hpp"
#include "solver/scenes/cost_probe.hpp"

namespace seedcal {
namespace {

// The confirmation takes about three rounds of replicates before it converges or stops.
constexpr int kConfirmRounds = 3;

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

}  // namespace

double RunPricer::probe(const RunPlan& plan, double confining_stress_pa) {
  double radii = 0.0;
  for (const SphereDef& sp : plan.body.spheres) radii += sp.radius_m;
  const auto key = std::make_tuple(plan.body.spheres.size(), plan.body.mass_kg, radii, confining_stress_pa);
  auto it = probes_.find(key);
  if (it == probes_.end()) {
    // A bed for the bulk scenes; one body in flight for a free drop or an impact.
    const CostProbe p = probe_sphere_step_cost(plan.physics, plan.body, plan.dt_s, threads_, plan.seeds > 2.0,
                                               plan.seeds > 2.0 ? confining_stress_pa : 0.0);
    probe_cpu_s_ += p.probe_cpu_s;
    it = probes_.emplace(key, p.cpu_s_per_sphere_step).first;
  }
  return it->second;
}

SceneCost RunPricer::price(const SceneFile& scene) {
  SceneCost c;
  c.kind = scene.kind;
  c.plan = plan_scene(scene);
  c.cpu_s_per_sphere_step = probe(c.plan, 0.0);
  for (const PlanPhase& ph : c.plan.phases) {
    const double sphere_steps = c.plan.dt_s > 0.0 ? ph.spheres * ph.simulated_s / c.plan.dt_s : 0.0;
    double cost = c.cpu_s_per_sphere_step;
    if (ph.confining_stress_pa > 0.0) {
      c.confining_stress_pa = ph.confining_stress_pa;
      c.cpu_s_per_sphere_step_loaded = cost = probe(c.plan, ph.confining_stress_pa);
    }
    c.cpu_s += sphere_steps * cost;
  }
  return c;
}

std::string describe_scene_cost(const std::string& what, const SceneCost& c) {
  if (!c.refused.empty()) {
    std::string why = c.refused;
    while (!why.empty() && (why.back() == '\n' || why.back() == ' ')) why.pop_back();
    for (char& ch : why)
      if (ch == '\n') ch = ' ';
    return "plan: " + what + ": refused by the scene, its runs will fail (priced at 0 CPU s): " + why;
  }
  return "plan: " + what + " (" + c.kind + "): " + fmt("%.0f", c.plan.seeds) + " seeds, " +
         fmt("%.0f", c.plan.spheres) + " spheres, " + fmt("%.3g", c.plan.simulated_s()) + " s simulated at dt " +
         fmt("%.3g", c.plan.dt_s) + " s (" + fmt("%.3g", c.plan.steps()) + " steps), " +
         fmt("%.0f", c.cpu_s_per_sphere_step * 1e9) + " ns a sphere-step" +
         (c.cpu_s_per_sphere_step_loaded > 0.0 ? " (" + fmt("%.0f", c.cpu_s_per_sphere_step_loaded * 1e9) + " under " +
                                                      fmt("%.3g", c.confining_stress_pa * 1e-3) + " kPa)"
                                                : std::string()) +
         ": ~" + fmt("%.3g", c.cpu_s) +
         " CPU s a run";
}

StudyCostEstimate estimate_study_cost(const StudyConfig& s, int threads) {
  StudyCostEstimate e;
  nlohmann::json nominal = nlohmann::json::object();
  for (const StudyParameter& p : s.parameters) nominal[p.path] = p.nominal;
  RunPricer pricer(threads);
  const int T = static_cast<int>(s.targets.size());
  // cost[m][t]: one run of scene t under model m.
  std::vector<std::vector<double>> cost(s.models.size(), std::vector<double>(static_cast<std::size_t>(s.scene_count())));
  for (std::size_t m = 0; m < s.models.size(); ++m) {
    for (int t = 0; t < s.scene_count(); ++t) {
      const StudyTarget& test = s.scene_of(t);
      SceneCost c;
      try {
        c = pricer.price(load_scene_file(test.scene, scene_overrides(s.models[m], test, nominal)));
      } catch (const InputError& err) {
        // A model the scene refuses (a time step above the stable limit, say) is the study's to
        // report run by run, as its runs fail; the estimate names it and goes on.
        c.kind = test.scene;
        c.refused = err.what();
      }
      c.test = test.name;
      c.model = s.models[m].name;
      cost[m][static_cast<std::size_t>(t)] = c.cpu_s;
      e.scenes.push_back(std::move(c));
    }
  }
  e.probe_cpu_s = pricer.probe_cpu_s();
  // Calibration: runs of every target (under the first model) at each planned point.
  double per_point = 0.0;
  for (int t = 0; t < T; ++t) per_point += cost[0][static_cast<std::size_t>(t)];
  // The calibration's batches as the scenes of their runs, in order (the first model's stages; a
  // model calibrated too under calibrate_each_model runs the same), priced under model m.
  std::vector<std::vector<int>> calibration_batches;
  const auto priced = [&](const std::vector<int>& scenes, std::size_t m) {
    std::vector<double> batch;
    for (const int t : scenes) batch.push_back(cost[m][static_cast<std::size_t>(t)]);
    return batch;
  };
  // A batch of calibration points: a run of every target at each.
  const auto add_points_batch = [&](int points, StageRuns& r) {
    std::vector<int>& scenes = calibration_batches.emplace_back();
    for (int p = 0; p < points; ++p)
      for (int t = 0; t < T; ++t) scenes.push_back(t);
    r.batches.push_back(priced(scenes, 0));
  };
  auto add = [&](const std::string& stage, int points_expected, int points_most, int replicates) {
    StageRuns r{stage, points_expected * replicates * T, points_most * replicates * T, 0.0, {}};
    r.cpu_s = points_expected * replicates * per_point;
    if (points_expected > 0) add_points_batch(points_expected * replicates, r);
    e.stages.push_back(r);
  };
  int calibrated = 0;
  for (const StudyParameter& p : s.parameters) calibrated += p.calibrate ? 1 : 0;
  const int kept = std::clamp(calibrated, 2, static_cast<int>(s.parameters.size()));
  const auto design = static_cast<int>(surrogate_design(s, kept).rows());
  add("screening", s.screen.runs, s.screen.runs, s.screen.replicates);
  add("ascent", 0, s.ascent.max_steps, s.screen.replicates);
  add("surrogate", design, design, s.surrogate.replicates);
  int before = 0;
  for (const StageRuns& r : e.stages) before += r.runs;
  const int confirm_runs = std::max(0, std::min(kConfirmRounds * s.confirm.replicates * T, s.confirm.max_evaluations - before));
  StageRuns confirm{"confirmation", confirm_runs, std::max(0, s.confirm.max_evaluations - before), 0.0, {}};
  confirm.cpu_s = T > 0 ? static_cast<double>(confirm_runs) / T * per_point : 0.0;
  // Round by round: each round's replicates of every target.
  for (int left = T > 0 ? confirm_runs / T : 0; left > 0; left -= std::max(1, s.confirm.replicates))
    add_points_batch(std::min(left, std::max(1, s.confirm.replicates)), confirm);
  e.stages.push_back(confirm);
  // The pick along the solution curve (curve_stage.cpp), expected when one target has two
  // parameters to calibrate: the named test at every point, or every candidate at the curve's
  // ends and (priced as the dearest of them) the rest. Its test then needs no verification runs
  // under the first model.
  const std::vector<int> candidates = curve_candidates(s);
  int curve_scene = -1;
  if (T == 1 && calibrated == 2 && s.verify.curve_points > 0 && !candidates.empty()) {
    StageRuns curve{"curve", 0, 0, 0.0, {}};
    const int n = s.verify.curve_points;
    curve_scene = candidates.front();
    for (const int c : candidates)
      if (cost[0][static_cast<std::size_t>(c)] > cost[0][static_cast<std::size_t>(curve_scene)]) curve_scene = c;
    std::vector<int>& scenes = calibration_batches.emplace_back();
    if (candidates.size() > 1) {
      for (const int c : candidates) scenes.insert(scenes.end(), 2, c);
      scenes.insert(scenes.end(), static_cast<std::size_t>(n - 2), curve_scene);  // n >= 3 (study_config.cpp)
    } else {
      scenes.assign(static_cast<std::size_t>(n), curve_scene);
    }
    curve.batches.push_back(priced(scenes, 0));
    curve.runs = static_cast<int>(scenes.size());
    for (const double c : curve.batches.back()) curve.cpu_s += c;
    curve.at_most = curve.runs;
    e.stages.push_back(curve);
  }
  // [verify] calibrate_each_model: every other model repeats the calibration and the curve under
  // its own overrides (the same runs, each priced under that model).
  const bool each_model = s.verify.calibrate_each_model && s.models.size() > 1;
  if (each_model) {
    int runs = 0, most = 0, curve_runs = 0;
    double points = 0.0;  // calibration points of every target
    for (const StageRuns& r : e.stages) {
      if (r.stage == "curve") {
        curve_runs = r.runs;
        continue;
      }
      runs += r.runs;
      most += r.at_most;
      points += T > 0 ? static_cast<double>(r.runs) / T : 0.0;
    }
    for (std::size_t m = 1; m < s.models.size(); ++m) {
      double per_point_m = 0.0;
      for (int t = 0; t < T; ++t) per_point_m += cost[m][static_cast<std::size_t>(t)];
      StageRuns r{"calibration of \"" + s.models[m].name + "\"", runs + curve_runs, most + curve_runs, points * per_point_m, {}};
      if (curve_scene >= 0) r.cpu_s += curve_runs * cost[m][static_cast<std::size_t>(curve_scene)];
      for (const std::vector<int>& scenes : calibration_batches) r.batches.push_back(priced(scenes, m));
      e.stages.push_back(r);
    }
  }
  // Verification: every scene under every model, its replicates each.
  if (!s.checks.empty() || s.models.size() > 1) {
    // One batch in model order, each model's tests in order (verify_stage.cpp).
    StageRuns verify{"verification", 0, 0, 0.0, {{}}};
    for (std::size_t m = 0; m < s.models.size(); ++m)
      for (int t = 0; t < s.scene_count(); ++t) {
        const StudyTarget& test = s.scene_of(t);
        const int reps = test.replicates > 0 && t >= T ? test.replicates : s.verify.replicates;
        verify.at_most += reps;
        if ((m == 0 || each_model) && t == curve_scene) continue;
        verify.runs += reps;
        verify.cpu_s += reps * cost[m][static_cast<std::size_t>(t)];
        verify.batches.front().insert(verify.batches.front().end(), static_cast<std::size_t>(reps), cost[m][static_cast<std::size_t>(t)]);
      }
    e.stages.push_back(verify);
  }
  for (const StageRuns& r : e.stages) {
    e.runs += r.runs;
    e.cpu_s += r.cpu_s;
  }
  // The most: the calibration's budget (every run of it a point of every target), then the curve
  // and the whole verification.
  const int calibration_most = std::max(s.confirm.max_evaluations, before);
  e.runs_at_most = calibration_most;
  e.cpu_s_at_most = T > 0 ? static_cast<double>(calibration_most) / T * per_point : 0.0;
  for (const StageRuns& r : e.stages) {
    const bool other_model = r.stage.rfind("calibration of ", 0) == 0;
    if (r.stage != "curve" && r.stage != "verification" && !other_model) continue;
    e.runs_at_most += r.at_most;
    // Another model's calibration at most: its budget, priced as its expected runs are.
    e.cpu_s_at_most += other_model && r.runs > 0 ? r.cpu_s * r.at_most / r.runs : r.cpu_s;
  }
  if (curve_scene >= 0 && e.stages.back().stage == "verification") {
    const StudyTarget& test = s.scene_of(curve_scene);
    const int reps = test.replicates > 0 ? test.replicates : s.verify.replicates;
    for (std::size_t m = 0; m < (each_model ? s.models.size() : 1); ++m)
      e.cpu_s_at_most += reps * cost[m][static_cast<std::size_t>(curve_scene)];
  }
  return e;
}

double stages_wall_s(const std::vector<StageRuns>& stages, int slots) {
  const auto n = static_cast<std::size_t>(std::max(1, slots));
  double wall = 0.0;
  std::vector<double> free_at(n);
  for (const StageRuns& r : stages)
    for (const std::vector<double>& batch : r.batches) {
      std::fill(free_at.begin(), free_at.end(), 0.0);
      for (const double c : batch) *std::min_element(free_at.begin(), free_at.end()) += c;
      wall += *std::max_element(free_at.begin(), free_at.end());
    }
  return wall;
}

std::vector<std::string> describe_cost(const StudyCostEstimate& e, int slots) {
  std::vector<std::string> out;
  for (const SceneCost& c : e.scenes)
    out.push_back(describe_scene_cost("test \"" + c.test + "\" under model \"" + c.model + "\"", c));
  for (const StageRuns& r : e.stages) {
    std::string line = "plan: " + r.stage + ": " + std::to_string(r.runs) + " DEM runs";
    if (r.at_most != r.runs) line += " (at most " + std::to_string(r.at_most) + ")";
    out.push_back(line + ", ~" + fmt("%.0f", r.cpu_s) + " CPU s");
  }
  const int n = std::max(1, slots);
  out.push_back("plan: in all ~" + std::to_string(e.runs) + " DEM runs (at most " + std::to_string(e.runs_at_most) +
                "), ~" + fmt("%.0f", e.cpu_s) + " CPU s (at most " + fmt("%.0f", e.cpu_s_at_most) + "), ~" +
                clock_text(stages_wall_s(e.stages, n)) + " on " + std::to_string(n) + " slot" + (n > 1 ? "s" : "") +
                "; measuring this machine took " + fmt("%.2g", e.probe_cpu_s) + " CPU s");
  return out;
}

}  // namespace seedcal
