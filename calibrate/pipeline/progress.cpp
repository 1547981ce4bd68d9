#include "calibrate/pipeline/progress.hpp"

#include <cmath>
#include <cstdio>
#include <ctime>
#include <iostream>

namespace seedcal {

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

std::string clock_text(double s) {
  if (!std::isfinite(s) || s < 0) return "?";
  const long v = std::lround(s);
  char buf[32];
  std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", v / 3600, (v / 60) % 60, v % 60);
  return buf;
}

Progress::Progress(const std::string& log_path, bool terminal, int slots)
    : log_(log_path, std::ios::app), terminal_(terminal), slots_(slots > 0 ? slots : 1),
      start_(std::chrono::steady_clock::now()) {}

Progress::~Progress() {
  if (terminal_) std::cerr << "\n";
}

double Progress::elapsed_seconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void Progress::stage(const std::string& name, int planned) {
  stage_ = name;
  planned_ = planned;
  done_ = 0;
  log("stage " + name + ": " + std::to_string(planned) + " DEM runs planned");
}

void Progress::run_done(bool reused, double wall_seconds, const std::string& what) {
  if (!reused) {
    run_wall_sum_ += wall_seconds;
    ++run_wall_count_;
  }
  count_run(reused ? " (from the store) " : " ", what);
}

void Progress::run_skipped(const std::string& what) { count_run(" (skipped) ", what); }

void Progress::count_run(const char* tag, const std::string& what) {
  ++done_;
  ++total_done_;
  log_ << utc_now() << " " << stage_ << " " << done_ << "/" << planned_ << tag << what << "\n";
  log_.flush();
  draw();
}

void Progress::best_error(double relative_error) {
  if (best_ < 0 || std::fabs(relative_error) < best_) best_ = std::fabs(relative_error);
}

void Progress::log(const std::string& message) {
  log_ << utc_now() << " " << message << "\n";
  log_.flush();
  if (terminal_) std::cerr << "\r\033[K" << message << "\n";
  draw();
}

void Progress::draw() {
  if (!terminal_) return;
  const double per_run = run_wall_count_ > 0 ? run_wall_sum_ / run_wall_count_ : NAN;
  const double left = per_run * std::max(0, planned_ - done_) / slots_;
  char best[32] = "-";
  if (best_ >= 0) std::snprintf(best, sizeof best, "%.2f %%", 100.0 * best_);
  std::cerr << "\r\033[K[" << stage_ << "] " << done_ << "/" << planned_ << " runs (" << total_done_
            << " in all), best error " << best << ", elapsed " << clock_text(elapsed_seconds())
            << ", stage left ~" << clock_text(left) << std::flush;
}

}  // namespace seedcal
