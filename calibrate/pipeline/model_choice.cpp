#include "calibrate/pipeline/model_choice.hpp"

#include <cmath>
#include <cstdio>

namespace seedcal {

ModelChoice choose_model(const std::vector<ModelScore>& models, double margin, double z) {
  ModelChoice out;
  const int n = static_cast<int>(models.size());
  out.tied.assign(static_cast<std::size_t>(n), false);
  for (int m = 0; m < n; ++m) {
    const double e = models[static_cast<std::size_t>(m)].error;
    if (std::isfinite(e) && (out.best < 0 || e < models[static_cast<std::size_t>(out.best)].error)) out.best = m;
  }
  if (out.best < 0) {
    out.comparison = "no model has an error on every test with an experimental value";
    return out;
  }
  const ModelScore& b = models[static_cast<std::size_t>(out.best)];
  // Model m's excess error over the best and the standard error of that difference.
  const auto excess_of = [&](int m) { return models[static_cast<std::size_t>(m)].error - b.error; };
  const auto se_of = [&](int m) {
    const double s = models[static_cast<std::size_t>(m)].error_se;
    return std::sqrt(s * s + b.error_se * b.error_se);
  };
  for (int m = 0; m < n; ++m) {
    const ModelScore& x = models[static_cast<std::size_t>(m)];
    if (!std::isfinite(x.error)) continue;
    const double excess = excess_of(m), se = se_of(m);
    const double allowance = margin + (std::isfinite(se) ? z * se : 0.0);
    out.tied[static_cast<std::size_t>(m)] = m == out.best || excess <= allowance;
    if (out.tied[static_cast<std::size_t>(m)] &&
        (out.chosen < 0 || x.cost < models[static_cast<std::size_t>(out.chosen)].cost))
      out.chosen = m;
  }
  const ModelScore& c = models[static_cast<std::size_t>(out.chosen)];
  char text[480];
  if (out.chosen == out.best) {
    out.replicates_factor = 1.0;
    std::snprintf(text, sizeof text,
                  "the most accurate model (mean |relative error| %.2f %%) is also the cheapest of those within %.2f "
                  "points of it plus the scatter",
                  100.0 * b.error, 100.0 * margin);
  } else {
    const double excess = excess_of(out.chosen), se = se_of(out.chosen);
    if (excess <= margin || !std::isfinite(se) || se == 0.0) {
      out.replicates_factor = -1.0;
    } else {
      const double r = z * se / (excess - margin);
      out.replicates_factor = r * r;
    }
    char scatter[96];
    if (std::isfinite(se)) std::snprintf(scatter, sizeof scatter, "%.2f points", 100.0 * z * se);
    else std::snprintf(scatter, sizeof scatter, "an unknown scatter (single runs)");
    std::snprintf(text, sizeof text,
                  "mean |relative error| %.2f %% against the lowest %.2f %%: %.2f points more, within the margin of %.2f "
                  "points plus %s (%.3g standard errors of the difference), so the two cannot be told apart and the "
                  "cheaper is chosen",
                  100.0 * c.error, 100.0 * b.error, 100.0 * excess, 100.0 * margin, scatter, z);
  }
  out.comparison = text;
  return out;
}

}  // namespace seedcal
