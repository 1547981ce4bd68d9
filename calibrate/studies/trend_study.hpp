#pragma once
// Does an index move the way physics says when one setting changes (`seedcal study trend`,
// docs/studies.md)? The scene runs at every level of one key (a dotted TOML path, e.g.
// seed_seed.static_friction or drum.quick.speed_rpm) with the same seeds at every level, so the
// differences are the setting's. A trend is confirmed when every step between neighbouring levels
// goes the expected way and the change from the first to the last level exceeds `sd_multiple`
// pooled sample standard deviations of the index:
//   s_p = sqrt(((n_a - 1) s_a^2 + (n_b - 1) s_b^2) / (n_a + n_b - 2))
// (the run-to-run scatter of one seed, not the standard error of a mean: a trend that passes is
// visible in single runs, not only in averages).
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "calibrate/studies/study_progress.hpp"

namespace seedcal {

struct TrendOptions {
  std::string scene;               // a scene file
  std::string metric;              // index key of metrics.json; empty: the scene's own index
  std::vector<std::string> sets;   // overrides for every level (e.g. fidelity=quick)
  std::string key;                 // the dotted TOML path that changes
  std::vector<double> levels;      // at least two, in the order the trend is read
  std::string expect = "rise";     // "rise" or "fall" along `levels`
  double sd_multiple = 2.0;
  int repeats = 3;                 // seeds seed, seed + 1, ... at every level
  int threads = 1;                 // OpenMP threads per simulation
  int jobs = 1;                    // runs (one level, one seed) simulated at once, one thread each
  std::uint64_t seed = 1;
  std::string out_dir;             // scenes write their CSV and pictures below it
  StudyProgress* progress = nullptr;  // told of every run (optional)
};

// Its DEM runs, level by level.
std::vector<PlannedRuns> trend_plan(const TrendOptions& o);

// Pooled sample sd of two samples (NaN with fewer than two values in all).
double pooled_sd(const std::vector<double>& a, const std::vector<double>& b);

nlohmann::json trend_study(const TrendOptions& o);

// Levels and steps as CSV (header first).
std::string trend_csv(const nlohmann::json& study);

}  // namespace seedcal
