#pragma once
// The solution curve of one target in two unknowns: the level set {u in [-1, 1]^2 : f(u) = c} of a
// fitted surface, traced as a polyline, and positions along it by arc length.
//
// Tracing: f - c is scanned on lines of constant u1 and of constant u2 (so a steep stretch of the
// curve is found as densely as a flat one) and every sign change is refined by bisection. The
// roots fall into branches (neighbours at most `max_gap` apart); the branch holding the root nearest
// `anchor` is kept and ordered along its principal axis (the eigenvector of the largest eigenvalue
// of its points' covariance): the curve in order for a branch monotone along that axis.
#include <vector>

#include <Eigen/Dense>

#include "doe/rsm/surface_optimum.hpp"

namespace seedcal::doe {

struct LevelCurveOptions {
  int lines = 41;          // scan lines per direction across [-1, 1]
  int samples = 201;       // points per scan line between which sign changes are sought
  double max_gap = 0.25;   // coded distance beyond which two roots belong to different branches
  Eigen::Vector2d anchor = Eigen::Vector2d::Zero();  // the branch nearest this point is kept
};

// A polyline in the coded box, parametrised by its normalised arc length s in [0, 1].
class CurvePath {
 public:
  CurvePath() = default;
  explicit CurvePath(std::vector<Eigen::Vector2d> points);  // in order along the curve

  bool usable() const { return points_.size() >= 2 && length_ > 0.0; }
  const std::vector<Eigen::Vector2d>& points() const { return points_; }
  double length() const { return length_; }
  // The point at normalised arc length s (clamped to [0, 1]).
  Eigen::Vector2d at(double s) const;
  // Normalised arc length of the point of the curve nearest u.
  double project(const Eigen::Vector2d& u) const;

 private:
  std::vector<Eigen::Vector2d> points_;
  std::vector<double> cumulative_;  // arc length up to each point
  double length_ = 0.0;
};

// The curve f(u) = target over [-1, 1]^2 (see the file comment); not usable() when f does not
// cross the target in the box.
CurvePath trace_level_curve(const Surface& f, double target, const LevelCurveOptions& options = {});

}  // namespace seedcal::doe
