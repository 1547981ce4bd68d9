#include "calibrate/studies/study_progress.hpp"

#include <algorithm>
#include <cstdio>
#include <iostream>

#include "calibrate/pipeline/progress.hpp"
#include "store/errors.hpp"

namespace seedcal {

StudyPlanEstimate estimate_study_plan(const std::vector<PlannedRuns>& plan, int threads) {
  StudyPlanEstimate e;
  RunPricer pricer(threads);
  for (const PlannedRuns& p : plan) {
    SceneCost c;
    try {
      c = pricer.price(load_scene_file(p.scene, p.sets));
    } catch (const InputError& refused) {
      // Bad input, as the study would say before its first run, unless the study records the
      // refusal as a row (tradeoff_study.cpp), which costs nothing.
      if (!p.refusal_is_a_row) throw;
      c.kind = "refused";
      c.test = refused.what();
      e.rows.emplace_back(p, c);
      continue;
    }
    e.runs += p.runs;
    e.cpu_s += p.runs * c.cpu_s;
    e.rows.emplace_back(p, c);
  }
  e.probe_cpu_s = pricer.probe_cpu_s();
  return e;
}

std::vector<std::string> describe_study_plan(const std::string& kind, const StudyPlanEstimate& e, int slots) {
  std::vector<std::string> out;
  for (const auto& [p, c] : e.rows)
    out.push_back(c.kind == "refused"
                      ? "plan: " + p.label + ": refused by the scene, not run (" + c.test + ")"
                      : describe_scene_cost(p.label + ", " + std::to_string(p.runs) + " run" + (p.runs > 1 ? "s" : ""), c));
  const int n = std::max(1, slots);
  char buf[256];
  std::snprintf(buf, sizeof buf, "plan: study %s: %d DEM runs, ~%.0f CPU s, ~%s on %d slot%s; measuring this machine took %.2g CPU s",
                kind.c_str(), e.runs, e.cpu_s, clock_text(e.cpu_s / n).c_str(), n, n > 1 ? "s" : "", e.probe_cpu_s);
  out.push_back(buf);
  return out;
}

nlohmann::json study_plan_json(const StudyPlanEstimate& e) {
  nlohmann::json rows = nlohmann::json::array();
  for (const auto& [p, c] : e.rows)
    rows.push_back({{"label", p.label}, {"scene", p.scene}, {"sets", p.sets}, {"runs", p.runs}, {"kind", c.kind},
                    {"seeds", c.plan.seeds}, {"spheres", c.plan.spheres}, {"simulated_s", c.plan.simulated_s()},
                    {"dt_s", c.plan.dt_s}, {"cpu_s_per_run", c.cpu_s}});
  return {{"runs", e.runs}, {"cpu_s", e.cpu_s}, {"probe_cpu_s", e.probe_cpu_s}, {"rows", rows}};
}

StudyProgress::StudyProgress(std::string kind, const StudyPlanEstimate& estimate, int slots, bool terminal)
    : kind_(std::move(kind)), rows_(estimate.rows), planned_(estimate.runs), estimated_cpu_s_(estimate.cpu_s),
      slots_(std::max(1, slots)), on_(terminal), start_(std::chrono::steady_clock::now()) {}

StudyProgress::~StudyProgress() { clear(); }

void StudyProgress::clear() {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (on_) std::cerr << "\r\033[K" << std::flush;
  on_ = false;
}

void StudyProgress::scene_done(const std::string& scene, const std::vector<std::string>& sets,
                               const nlohmann::json& metrics) {
  double per_run = 0.0;
  for (const auto& [p, c] : rows_)
    if (p.scene == scene && p.sets == sets) per_run = c.cpu_s;
  const int runs = metrics.contains("runs") ? static_cast<int>(metrics["runs"].size()) : 1;
  runs_done(runs, runs * per_run, metrics.value("cpu_seconds", 0.0));
}

void StudyProgress::runs_done(int runs, double estimated_cpu_s, double cpu_s) {
  const std::lock_guard<std::mutex> lock(mutex_);
  done_ += runs;
  done_estimated_s_ += estimated_cpu_s;
  done_cpu_s_ += cpu_s;
  if (!on_) return;
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  // What is left of the estimate, scaled by how the runs so far compared with theirs, over the slots.
  const double scale = done_estimated_s_ > 0.0 && done_cpu_s_ > 0.0 ? done_cpu_s_ / done_estimated_s_ : 1.0;
  const double left = std::max(0.0, estimated_cpu_s_ - done_estimated_s_) * scale / slots_;
  std::cerr << "\r\033[K[" << kind_ << "] " << done_ << "/" << planned_ << " DEM runs, elapsed "
            << clock_text(elapsed) << ", left ~" << clock_text(left) << std::flush;
}

}  // namespace seedcal
