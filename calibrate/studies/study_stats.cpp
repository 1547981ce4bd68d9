#include "calibrate/studies/study_stats.hpp"

#include <cmath>
#include <limits>

#include <gsl/gsl_statistics_double.h>

namespace seedcal {
nlohmann::json number_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

nlohmann::json sample_stats(const std::vector<double>& x) {
  const double mean = x.empty() ? kNaN : gsl_stats_mean(x.data(), 1, x.size());
  const double sd = x.size() < 2 ? kNaN : gsl_stats_sd_m(x.data(), 1, x.size(), mean);
  return {{"mean", number_or_null(mean)}, {"sd", number_or_null(sd)}, {"n", x.size()}, {"samples", x}};
}

std::vector<double> per_run(const nlohmann::json& m, const std::string& key) {
  std::vector<double> out;
  auto take = [&](const nlohmann::json& r) {
    if (r.value("status", "ok") == "ok" && r.contains(key) && r[key].is_number() && std::isfinite(r[key].get<double>()))
      out.push_back(r[key].get<double>());
  };
  if (m.contains("runs")) {
    for (const auto& r : m["runs"]) take(r);
  } else {
    take(m);
  }
  return out;
}

double mean_of(const nlohmann::json& s) { return s["mean"].is_number() ? s["mean"].get<double>() : kNaN; }

}  // namespace seedcal
