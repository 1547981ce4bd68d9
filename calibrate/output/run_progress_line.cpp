#include "calibrate/output/run_progress_line.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "calibrate/pipeline/progress.hpp"

namespace seedcal {
namespace {

constexpr double kRedraw_s = 0.25;

double seconds(std::chrono::steady_clock::duration d) { return std::chrono::duration<double>(d).count(); }

}  // namespace

RunProgressLine::RunProgressLine(const RunPlan& plan, int runs, int jobs, bool on)
    : planned_s_(plan.simulated_s()), runs_(std::max(1, runs)), jobs_(std::max(1, jobs)), on_(on),
      state_(static_cast<std::size_t>(std::max(1, runs))), start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

RunProgressLine::~RunProgressLine() { clear(); }

void RunProgressLine::clear() {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (on_) std::cerr << "\r\033[K" << std::flush;
  on_ = false;
}

std::string RunProgressLine::format(std::size_t run, int runs, double t_s, double planned_s, std::size_t spheres,
                                    double steps_per_s, double elapsed_s, double left_s) {
  char buf[256];
  char rate[48] = "measuring steps/s";
  if (steps_per_s > 0.0) std::snprintf(rate, sizeof rate, "%.0f steps/s", steps_per_s);
  std::snprintf(buf, sizeof buf, "run %zu/%d: t = %.3f of ~%.3g s simulated, %zu spheres, %s, elapsed %s, left ~%s",
                run + 1, runs, t_s, planned_s, spheres, rate, clock_text(elapsed_s).c_str(),
                clock_text(left_s).c_str());
  return buf;
}

void RunProgressLine::update(std::size_t run, const Simulation& sim) {
  if (run >= state_.size()) return;
  const auto now = std::chrono::steady_clock::now();
  const std::lock_guard<std::mutex> lock(mutex_);
  if (!on_) return;
  RunState& r = state_[run];
  if (r.step > 0 && sim.step_count() > r.step) {
    const double dt = seconds(now - r.last);
    if (dt > 0.0) r.steps_per_s = static_cast<double>(sim.step_count() - r.step) / dt;
  }
  if (r.step == 0 || seconds(now - r.last) >= kRedraw_s) {
    r.step = sim.step_count();
    r.last = now;
  }
  r.t_s = sim.time_s();
  // Runs are taken in index order, jobs_ at a time: every run more than jobs_ - 1 below this one
  // has finished.
  for (std::size_t k = 0; k + static_cast<std::size_t>(jobs_) <= run; ++k) state_[k].t_s = std::max(state_[k].t_s, planned_s_);
  if (seconds(now - last_draw_) < kRedraw_s) return;
  last_draw_ = now;
  // Time left: the simulated time still planned over the rate at which simulated time has passed.
  double done = 0.0;
  for (const RunState& s : state_) done += std::min(s.t_s, planned_s_);
  const double elapsed = seconds(now - start_);
  const double left_sim = std::max(0.0, planned_s_ * static_cast<double>(runs_) - done);
  const double left = done > 0.0 ? left_sim * elapsed / done : -1.0;
  // A run just started has no rate of its own yet: the last measured one stands for it.
  if (r.steps_per_s > 0.0) last_rate_ = r.steps_per_s;
  std::cerr << "\r\033[K" << format(run, runs_, r.t_s, planned_s_, sim.spheres().size(), last_rate_, elapsed, left)
            << std::flush;
}

}  // namespace seedcal
