#pragma once
// Statistics the studies share: mean and sample sd of one metric over the runs of a repeated
// scene (`run_scene_file` with repeats keeps every run under "runs"), failed runs left out.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "doe/core/numbers.hpp"

namespace seedcal {

// A statistic with too few values: the same NaN as doe/'s.
using doe::kNaN;

// A finite number, or null (JSON has no NaN).
nlohmann::json number_or_null(double v);

// {"mean", "sd" (n - 1), "n", "samples"} by GSL; mean/sd are null when there are too few values.
nlohmann::json sample_stats(const std::vector<double>& x);

// The values of `key` in every run of a scene result whose status is ok (a run stopped by a guard
// has no index: it is left out, and the study reports the failure beside the statistics).
std::vector<double> per_run(const nlohmann::json& scene_metrics, const std::string& key);

// The "mean" of a sample_stats object, NaN when it has none.
double mean_of(const nlohmann::json& stats);

}  // namespace seedcal
