#include "doe/rsm/level_curve.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>

#include "doe/core/errors.hpp"

namespace seedcal::doe {
namespace {

// Roots of g on [-1, 1] from `samples` points and bisection on each sign change.
template <class G>
void roots_on_line(const G& g, int samples, std::vector<double>* out) {
  double va = -1.0, ga = g(va);
  for (int j = 1; j < samples; ++j) {
    const double vb = -1.0 + 2.0 * j / (samples - 1), gb = g(vb);
    if (ga == 0.0) {
      out->push_back(va);
    } else if (ga * gb < 0.0) {
      double lo = va, hi = vb, glo = ga;
      for (int it = 0; it < 60; ++it) {
        const double m = 0.5 * (lo + hi), gm = g(m);
        if (glo * gm <= 0.0) {
          hi = m;
        } else {
          lo = m;
          glo = gm;
        }
      }
      out->push_back(0.5 * (lo + hi));
    }
    va = vb;
    ga = gb;
  }
  if (ga == 0.0) out->push_back(va);
}

}  // namespace

CurvePath::CurvePath(std::vector<Eigen::Vector2d> points) : points_(std::move(points)) {
  cumulative_.assign(points_.size(), 0.0);
  for (std::size_t i = 1; i < points_.size(); ++i) cumulative_[i] = cumulative_[i - 1] + (points_[i] - points_[i - 1]).norm();
  length_ = cumulative_.empty() ? 0.0 : cumulative_.back();
}

Eigen::Vector2d CurvePath::at(double s) const {
  if (points_.empty()) return Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN());
  if (!usable()) return points_.front();
  const double d = std::clamp(s, 0.0, 1.0) * length_;
  const auto it = std::upper_bound(cumulative_.begin(), cumulative_.end(), d);
  if (it == cumulative_.end()) return points_.back();
  const auto i = static_cast<std::size_t>(it - cumulative_.begin());  // cumulative_[i-1] <= d < cumulative_[i]
  const double seg = cumulative_[i] - cumulative_[i - 1];
  const double f = seg > 0.0 ? (d - cumulative_[i - 1]) / seg : 0.0;
  return points_[i - 1] + f * (points_[i] - points_[i - 1]);
}

double CurvePath::project(const Eigen::Vector2d& u) const {
  if (!usable()) return 0.0;
  double best = std::numeric_limits<double>::infinity(), s = 0.0;
  for (std::size_t i = 1; i < points_.size(); ++i) {
    const Eigen::Vector2d d = points_[i] - points_[i - 1];
    const double len2 = d.squaredNorm();
    const double f = len2 > 0.0 ? std::clamp((u - points_[i - 1]).dot(d) / len2, 0.0, 1.0) : 0.0;
    const double dist = (points_[i - 1] + f * d - u).squaredNorm();
    if (dist < best) {
      best = dist;
      s = (cumulative_[i - 1] + f * std::sqrt(len2)) / length_;
    }
  }
  return s;
}

CurvePath trace_level_curve(const Surface& f, double target, const LevelCurveOptions& o) {
  Problems p;
  p.require(o.lines >= 2, "LevelCurveOptions.lines", o.lines, "must be at least 2");
  p.require(o.samples >= 2, "LevelCurveOptions.samples", o.samples, "must be at least 2");
  p.require(o.max_gap > 0.0, "LevelCurveOptions.max_gap", o.max_gap, "must be positive");
  p.throw_if_any();
  std::vector<Eigen::Vector2d> cloud;
  std::vector<double> roots;
  for (int axis = 0; axis < 2; ++axis) {
    for (int i = 0; i < o.lines; ++i) {
      Eigen::VectorXd u(2);
      u(axis) = -1.0 + 2.0 * i / (o.lines - 1);
      const int free = 1 - axis;
      roots.clear();
      roots_on_line([&](double v) { u(free) = v; return f(u) - target; }, o.samples, &roots);
      for (const double r : roots) {
        Eigen::Vector2d q;
        q(axis) = u(axis);
        q(free) = r;
        cloud.push_back(q);
      }
    }
  }
  if (cloud.size() < 2) return CurvePath(cloud);
  // Branches: the connected components of the cloud with neighbours at most max_gap apart (single
  // linkage); the one holding the root nearest the anchor is kept.
  const std::size_t n = cloud.size();
  std::vector<std::size_t> parent(n);
  for (std::size_t i = 0; i < n; ++i) parent[i] = i;
  const auto root_of = [&](std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      if ((cloud[i] - cloud[j]).norm() <= o.max_gap) parent[root_of(i)] = root_of(j);
  std::size_t nearest = 0;
  for (std::size_t i = 1; i < n; ++i)
    if ((cloud[i] - o.anchor).norm() < (cloud[nearest] - o.anchor).norm()) nearest = i;
  const std::size_t branch = root_of(nearest);
  std::vector<Eigen::Vector2d> kept;
  for (std::size_t i = 0; i < n; ++i)
    if (root_of(i) == branch) kept.push_back(cloud[i]);
  // Order along the branch's principal axis (the eigenvector of the largest eigenvalue of the
  // points' covariance), increasing along the first factor (else the second).
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& q : kept) mean += q;
  mean /= static_cast<double>(kept.size());
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const auto& q : kept) cov += (q - mean) * (q - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
  Eigen::Vector2d axis = eig.eigenvectors().col(1);
  if (axis(0) < 0.0 || (axis(0) == 0.0 && axis(1) < 0.0)) axis = -axis;
  std::stable_sort(kept.begin(), kept.end(),
                   [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return (a - mean).dot(axis) < (b - mean).dot(axis); });
  // A root found by both scans once.
  std::vector<Eigen::Vector2d> ordered;
  for (const auto& q : kept)
    if (ordered.empty() || (q - ordered.back()).norm() > 1e-9) ordered.push_back(q);
  return CurvePath(std::move(ordered));
}

}  // namespace seedcal::doe
