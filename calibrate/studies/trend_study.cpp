#include "calibrate/studies/trend_study.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <sstream>

#include "calibrate/scenes/job_pool.hpp"
#include "calibrate/scenes/scene_file.hpp"
#include "calibrate/studies/study_stats.hpp"
#include "store/errors.hpp"

namespace seedcal {
namespace {


std::vector<double> samples_of(const nlohmann::json& level) {
  std::vector<double> v;
  for (const auto& x : level["index"]["samples"]) v.push_back(x.get<double>());
  return v;
}

// One comparison of two levels: the difference of the means, the pooled sd, their ratio, and
// whether the difference goes the expected way and beyond the required multiple.
nlohmann::json compare(const nlohmann::json& a, const nlohmann::json& b, double sign, double k) {
  const double d = mean_of(b["index"]) - mean_of(a["index"]);
  const double sp = pooled_sd(samples_of(a), samples_of(b));
  const double ratio = sp > 0.0 ? d / sp : kNaN;
  nlohmann::json c = {{"from", a["value"]}, {"to", b["value"]}, {"difference", number_or_null(d)},
                      {"pooled_sd", number_or_null(sp)}, {"difference_in_pooled_sd", number_or_null(ratio)}};
  c["expected_direction"] = std::isfinite(d) && sign * d > 0.0;
  c["beyond_required_sd"] = std::isfinite(ratio) && sign * ratio > k;
  return c;
}

}  // namespace

double pooled_sd(const std::vector<double>& a, const std::vector<double>& b) {
  auto ss = [](const std::vector<double>& v) {
    double m = 0.0, s = 0.0;
    for (double x : v) m += x;
    m /= static_cast<double>(v.size());
    for (double x : v) s += (x - m) * (x - m);
    return s;
  };
  const double dof = static_cast<double>(a.size() + b.size()) - 2.0;
  if (a.empty() || b.empty() || dof < 1.0) return kNaN;
  return std::sqrt((ss(a) + ss(b)) / dof);
}

namespace {

std::string level_set(const std::string& key, double level) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "%s=%.17g", key.c_str(), level);
  return buf;
}

}  // namespace

std::vector<PlannedRuns> trend_plan(const TrendOptions& o) {
  std::vector<PlannedRuns> plan;
  for (const double level : o.levels) {
    std::vector<std::string> sets = o.sets;
    sets.push_back(level_set(o.key, level));
    char label[256];
    std::snprintf(label, sizeof label, "%s=%.6g", o.key.c_str(), level);
    plan.push_back({label, o.scene, sets, o.repeats});
  }
  return plan;
}

nlohmann::json trend_study(const TrendOptions& o) {
  if (o.levels.size() < 2) throw InputError("--levels: give at least two values of " + o.key);
  if (o.expect != "rise" && o.expect != "fall")
    throw InputError("--expect = " + o.expect + ": allowed values are rise, fall");
  if (o.repeats < 2) throw InputError("--repeats = " + std::to_string(o.repeats) + ": a trend check needs at least 2 seeds per level (a pooled sd)");
  const double sign = o.expect == "rise" ? 1.0 : -1.0;
  std::string metric = o.metric;
  nlohmann::json j = {{"study", "trend"}, {"scene", o.scene}, {"sets", o.sets}, {"key", o.key}, {"expect", o.expect},
                      {"sd_multiple", o.sd_multiple}, {"repeats", o.repeats}, {"seed", o.seed}, {"jobs", o.jobs}};
  if (o.jobs < 1) throw InputError("--jobs = " + std::to_string(o.jobs) + ": allowed range 1 .. 1000");
  // Runs that share the process are timed by their own thread's CPU clock (run_cpu_seconds), which
  // counts a run's work only when it has one thread.
  if (o.jobs > 1 && o.threads > 1)
    throw InputError("--threads = " + std::to_string(o.threads) + " with --jobs = " + std::to_string(o.jobs) +
                     ": simulations run at once are one thread each (allowed: --threads 1), so that each "
                     "run's CPU time is its own");
  const std::size_t n = o.levels.size();
  std::vector<std::string> set(n), name(n);
  std::vector<SceneFile> scene(n);  // read once per level; its runs only read it
  std::vector<std::vector<std::string>> scene_sets(n);
  for (std::size_t i = 0; i < n; ++i) {
    char dir[64];
    std::snprintf(dir, sizeof dir, "level_%zu_%.4g", i, o.levels[i]);
    set[i] = level_set(o.key, o.levels[i]);
    name[i] = dir;
    std::vector<std::string> sets = o.sets;
    sets.push_back(set[i]);
    scene_sets[i] = sets;
    // Every level is checked before any runs: a bad key or value (the scene's own checks, exit 2)
    // at the last level is reported now, not after the other levels' simulations.
    scene[i] = load_scene_file(o.scene, sets);
    check_scene(scene[i]);
  }
  // Every run is independent (seed o.seed + r at every level, whatever the order), so `jobs` of
  // them run at once, each on its own thread with `threads` OpenMP threads, level by level. A
  // level's files come from its first seed, and its series ends at its first failed run, as in one
  // job: the results are those of one job.
  const std::size_t reps = static_cast<std::size_t>(o.repeats), tasks = n * reps;
  std::vector<nlohmann::json> run(tasks);
  std::vector<std::atomic<std::size_t>> first_failed(n);  // a level's first failed seed; reps: none
  for (auto& f : first_failed) f.store(reps);
  const std::vector<std::exception_ptr> errors = run_jobs(tasks, o.jobs, [&](std::size_t t) {
    const std::size_t i = t / reps, r = t % reps;
    if (r > first_failed[i].load()) return;  // after a failed run: not needed
    const std::string dir = o.out_dir.empty() || r > 0 ? std::string() : o.out_dir + "/scenes/" + name[i];
    run[t] = run_scene(scene[i], o.threads, o.seed + r, 1, dir);
    if (o.progress) o.progress->scene_done(o.scene, scene_sets[i], run[t]);
    if (run[t].value("status", "ok") != "ok") lower_to(first_failed[i], r);
  });
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
  nlohmann::json levels = nlohmann::json::array();
  for (std::size_t i = 0; i < n; ++i) {
    nlohmann::json row = {{"value", o.levels[i]}, {"set", set[i]}, {"status", "ok"}};
    // Every run's own metrics, seed by seed (a drum's frames and wall layer, a heap's sectors): what
    // the index alone does not say about the regime each level ran in.
    row["runs"] = nlohmann::json::array();
    std::vector<double> index, cpu;
    for (std::size_t r = 0; r < reps; ++r) {
      const nlohmann::json& m = run[i * reps + r];
      if (!m.is_null()) row["runs"].push_back(m);
      if (metric.empty()) metric = m.value("index_key", "");
      if (m.value("status", "ok") != "ok") {
        row["status"] = m["status"];
        row["failure"] = m.value("failure", nlohmann::json::object());
        break;  // later seeds of this level do not count, as in one job
      }
      const std::vector<double> x = per_run(m, metric);
      index.insert(index.end(), x.begin(), x.end());
      cpu.push_back(m.value("cpu_seconds", 0.0));
    }
    row["index"] = sample_stats(index);
    row["cpu_seconds_per_run"] = sample_stats(cpu)["mean"];
    levels.push_back(row);
  }
  nlohmann::json steps = nlohmann::json::array();
  bool monotone = true;
  for (std::size_t i = 0; i + 1 < levels.size(); ++i) {
    steps.push_back(compare(levels[i], levels[i + 1], sign, o.sd_multiple));
    monotone = monotone && steps.back()["expected_direction"].get<bool>();
  }
  const nlohmann::json overall = compare(levels.front(), levels.back(), sign, o.sd_multiple);
  bool complete = true;
  for (const auto& l : levels) complete = complete && l["index"]["n"].get<int>() == o.repeats;
  const bool confirmed = complete && monotone && overall["beyond_required_sd"].get<bool>();
  j["metric"] = metric;
  j["levels"] = levels;
  j["steps"] = steps;
  j["overall"] = overall;
  j["monotone"] = monotone;
  j["all_runs_ok"] = complete;
  j["confirmed"] = confirmed;
  std::ostringstream v;
  v.precision(3);
  const double ratio = overall["difference_in_pooled_sd"].is_number() ? overall["difference_in_pooled_sd"].get<double>() : kNaN;
  v << metric << (confirmed ? " confirmed to " : " not confirmed to ") << o.expect << " with " << o.key << ": first to last level "
    << ratio << " pooled sd (required " << sign * o.sd_multiple << ")" << (monotone ? ", every step the expected way" : ", not monotone")
    << (complete ? "" : ", some runs failed (see levels)");
  j["verdict"] = v.str();
  return j;
}

std::string trend_csv(const nlohmann::json& s) {
  std::ostringstream out;
  out.precision(10);
  auto cell = [](const nlohmann::json& x) { return x.is_number() ? x.dump() : std::string("n/a"); };
  out << "row,value,index_mean,index_sd,n,cpu_seconds_per_run,to,difference,pooled_sd,difference_in_pooled_sd,"
         "expected_direction,beyond_required_sd,status\n";
  for (const auto& l : s["levels"])
    out << "level," << cell(l["value"]) << "," << cell(l["index"]["mean"]) << "," << cell(l["index"]["sd"]) << ","
        << l["index"]["n"] << "," << cell(l["cpu_seconds_per_run"]) << ",,,,,,," << l["status"].get<std::string>() << "\n";
  auto step = [&](const char* kind, const nlohmann::json& c) {
    out << kind << "," << cell(c["from"]) << ",,,,," << cell(c["to"]) << "," << cell(c["difference"]) << ","
        << cell(c["pooled_sd"]) << "," << cell(c["difference_in_pooled_sd"]) << ","
        << (c["expected_direction"].get<bool>() ? "yes" : "no") << "," << (c["beyond_required_sd"].get<bool>() ? "yes" : "no")
        << ",\n";
  };
  for (const auto& c : s["steps"]) step("step", c);
  step("overall", s["overall"]);
  return out.str();
}

}  // namespace seedcal
