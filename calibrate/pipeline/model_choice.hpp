#pragma once
// The choice of clump model by accuracy and cost, aware of the simulations' scatter (stage 7,
// docs/calibrate.md): a model is preferred over a cheaper one only when its error is smaller beyond
// the scatter, and models whose errors cannot be told apart are tied, the cheapest of them chosen.
//
// Per model m: its error E_m (mean |relative error| over the tests with an experimental value), the
// standard error of that mean s_m (from the tests' replicate scatter, sqrt(sum_t se_t^2) / n_tests by
// the delta method; |e| moves one for one with e away from zero), and its cost c_m (CPU seconds of one
// run of every test). With b the model of the lowest error, m is tied with b when
//   E_m - E_b <= margin + z sqrt(s_m^2 + s_b^2),     z = 1.645 (one-sided 95 %),
// i.e. its excess error lies within the practical margin plus what the scatter allows. A model
// whose s is unknown (single runs with no pooled scatter) cannot be shown worse than b beyond
// the margin and counts as tied when within the margin only. The chosen model is the cheapest
// tied one that saves at least `cost_margin` of b's cost, c_m <= (1 - cost_margin) c_b, and b when
// none does: a model's CPU seconds come from single runs whose settling phases end at a criterion,
// on a machine other work shares, so a difference of a few percent is no reason to give up
// accuracy. To separate the cheapest tied model from b, each model's replicates would have to
// grow by the factor (z sqrt(s_m^2 + s_b^2) / (E_m - E_b - margin))^2 (the standard errors fall as
// 1/sqrt(n)); none when E_m - E_b <= margin (no replicate count can separate them).
#include <cstddef>
#include <string>
#include <vector>

namespace seedcal {

struct ModelScore {
  double error = 0.0;     // mean |relative error|; NaN: not comparable (a test without results)
  double error_se = 0.0;  // its standard error; NaN: unknown
  double cost = 0.0;      // CPU seconds of one run of every test
};

struct ModelChoice {
  int chosen = -1;             // -1 when no model has a finite error
  int best = -1;               // the lowest error
  std::vector<bool> tied;      // per model: tied with the best (the best is tied with itself)
  // Factor by which the replicates would have to grow to tell the chosen model from the best
  // (1 when they are the same model; < 0 when no count can: the difference is within the margin).
  double replicates_factor = 1.0;
  std::string comparison;      // the comparison in words, for the report
};

// z: one-sided normal quantile of the comparison (1.645: 95 %).
ModelChoice choose_model(const std::vector<ModelScore>& models, double margin, double cost_margin = 0.1,
                         double z = 1.6448536);

}  // namespace seedcal
