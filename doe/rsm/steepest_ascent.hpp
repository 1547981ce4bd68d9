#pragma once
// Path of steepest ascent (descent) from a first-order model y = b0 + sum b_j x_j in coded units
// (Box & Wilson 1951; Montgomery, DAE 8th ed., sec. 11.2): the path moves in proportion to the
// coefficients. With a base factor i and its step dx_i, every factor steps
//   dx_j = b_j / |b_i| * |dx_i|   (ascent; the sign flipped for descent),
// and run k of the path is x_k = x_0 + k dx.
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Dense>

namespace seedcal::doe {

struct SteepestAscentOptions {
  bool descent = false;        // follow -gradient (minimise)
  int base_factor = -1;        // -1: the factor with the largest |b_j|
  double base_step = 1.0;      // coded step of the base factor, > 0
  int max_steps = 20;
  double bound = 0.0;          // > 0: stop before a step leaves the coded box [-bound, bound]^k
  // Stopping rules while following the path with evaluations (follow_path):
  int stop_after_worse = 2;    // stop after this many consecutive steps that do not improve the best
  bool has_target = false;     // stop once the responses bracket `target` (one below, one above)
  double target = 0.0;
  bool IsValid(std::string* error) const;
};

// The per-step increment dx in coded units.
Eigen::VectorXd steepest_step(const Eigen::VectorXd& b, const SteepestAscentOptions& options);

// Points x_0 + k dx for k = 1..max_steps (fewer when `bound` cuts the path), one per row.
Eigen::MatrixXd steepest_path(const Eigen::VectorXd& b, const Eigen::VectorXd& origin, const SteepestAscentOptions& options);

struct PathResult {
  Eigen::MatrixXd points;          // the evaluated points, one per row
  std::vector<double> responses;
  int best = -1;                   // index of the best response (max for ascent, min for descent)
  std::string stop_reason;         // "no improvement", "target bracketed", "bound", "max steps"
};

// Evaluates f along the path, stopping by the rules above (Montgomery's Example 11.1 stops once
// the yield has fallen on two successive steps).
PathResult follow_path(const Eigen::VectorXd& b, const Eigen::VectorXd& origin,
                       const std::function<double(const Eigen::VectorXd&)>& f, const SteepestAscentOptions& options);

}  // namespace seedcal::doe
