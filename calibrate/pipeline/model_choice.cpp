#include "calibrate/pipeline/model_choice.hpp"

#include <cmath>
#include <cstdio>

namespace seedcal {

ModelChoice choose_model(const std::vector<ModelScore>& models, double margin, double cost_margin, double z) {
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
  }
  // The cheapest tied model, and whether it saves enough of the best's cost to be preferred.
  int cheapest = out.best;
  for (int m = 0; m < n; ++m)
    if (out.tied[static_cast<std::size_t>(m)] && models[static_cast<std::size_t>(m)].cost < models[static_cast<std::size_t>(cheapest)].cost)
      cheapest = m;
  const bool saves = models[static_cast<std::size_t>(cheapest)].cost <= (1.0 - cost_margin) * b.cost;
  out.chosen = saves ? cheapest : out.best;
  const ModelScore& c = models[static_cast<std::size_t>(out.chosen)];
  char text[480];
  if (out.chosen == out.best && cheapest != out.best) {
    out.replicates_factor = 1.0;
    std::snprintf(text, sizeof text,
                  "the most accurate model (mean |relative error| %.2f %%) is chosen: the cheapest model tied with it "
                  "saves %.1f %% of its CPU time, under the cost margin of %.0f %%",
                  100.0 * b.error, 100.0 * (1.0 - models[static_cast<std::size_t>(cheapest)].cost / b.cost),
                  100.0 * cost_margin);
  } else if (out.chosen == out.best) {
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
                  "cheaper is chosen (%.1f %% less CPU time)",
                  100.0 * c.error, 100.0 * b.error, 100.0 * excess, 100.0 * margin, scatter, z,
                  100.0 * (1.0 - c.cost / b.cost));
  }
  out.comparison = text;
  return out;
}

}  // namespace seedcal
