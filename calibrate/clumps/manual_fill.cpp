// Manual filling, as the paper describes its hand-made clumps (section 2.2 and its ref. [22]): the
// hilum is one sphere, the rest of the seed an ellipsoid filled with spheres along the principal
// axes whose outlines are as tangent to the surface as possible. Here "as tangent as possible" is
// made precise: the spheres' positions and radii maximise the intersection over union (IoU) with
// the target shape. Layout for N (odd, 5..15): three spheres on the length axis (centre, hilum at
// +x, tail at -x), and (N - 3) / 2 mirrored pairs, alternately in the x-y plane (+-y) and the
// x-z plane (+-z), each pair free to slide along x. The IoU is measured on lines parallel to x
// (exact along each line, so it is a continuous function of every parameter) over one quadrant
// y, z >= 0, which is enough because shape and clump are both mirror-symmetric in y and z; NLopt's
// Subplex (Rowan 1990, a derivative-free method robust on non-smooth objectives) maximises it
// from a fixed start, so the result is deterministic. Every sphere must reach the surface: the
// objective is penalised for each sphere that reaches less than min_protrusion of its radius out
// of the union of the others (a buried sphere adds no surface but sets the time step), and no
// radius is below min_radius_fraction of the smallest semi-axis.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <nlopt.hpp>

#include "calibrate/clumps/fill.hpp"
#include "solver/clump/buried_spheres.hpp"

namespace seedcal {
namespace {

struct Layout {
  int y_pairs = 0, z_pairs = 0;
  int params() const { return 6 + 3 * (y_pairs + z_pairs); }
};

Layout layout_for(int n) {
  Layout l;
  const int pairs = (n - 3) / 2;
  l.y_pairs = (pairs + 1) / 2;
  l.z_pairs = pairs / 2;
  return l;
}

// Parameters: [x_c, r_c, x_h, r_h, x_t, r_t, then per pair (x, offset, r)].
std::vector<SphereXYZR> spheres_from(const Layout& l, const double* p) {
  std::vector<SphereXYZR> s;
  s.push_back({Vec3(p[0], 0, 0), p[1]});
  s.push_back({Vec3(p[2], 0, 0), p[3]});
  s.push_back({Vec3(p[4], 0, 0), p[5]});
  int k = 6;
  for (int i = 0; i < l.y_pairs; ++i, k += 3) {
    s.push_back({Vec3(p[k], p[k + 1], 0), p[k + 2]});
    s.push_back({Vec3(p[k], -p[k + 1], 0), p[k + 2]});
  }
  for (int i = 0; i < l.z_pairs; ++i, k += 3) {
    s.push_back({Vec3(p[k], 0, p[k + 1]), p[k + 2]});
    s.push_back({Vec3(p[k], 0, -p[k + 1]), p[k + 2]});
  }
  return s;
}

// IoU over the quadrant y, z >= 0 on an n x n grid of x-lines; the shape's chords are cached.
struct QuadrantIoU {
  double y_max, z_max;
  int n;
  std::vector<std::vector<Interval>> shape_chords;
  std::vector<double> shape_len;
  QuadrantIoU(const Shape& shape, double reach, int grid) : n(grid) {
    const Aabb b = shape.bounds();
    y_max = b.hi.y() + reach;
    z_max = b.hi.z() + reach;
    shape_chords.resize(static_cast<std::size_t>(n) * n);
    shape_len.resize(shape_chords.size());
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        auto& c = shape_chords[static_cast<std::size_t>(i) * n + j];
        shape.chords(y_at(i), z_at(j), c);
        double s = 0;
        for (const auto& iv : c) s += iv[1] - iv[0];
        shape_len[static_cast<std::size_t>(i) * n + j] = s;
      }
  }
  double y_at(int i) const { return (i + 0.5) * y_max / n; }
  double z_at(int j) const { return (j + 0.5) * z_max / n; }
  double operator()(const std::vector<SphereXYZR>& spheres) const {
    double inter = 0, shape = 0, clump = 0;
    std::vector<Interval> c;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const auto idx = static_cast<std::size_t>(i) * n + j;
        sphere_chords(spheres, y_at(i), z_at(j), c);
        const auto& a = shape_chords[idx];
        shape += shape_len[idx];
        std::size_t p = 0, q = 0;
        while (p < a.size() && q < c.size()) {
          const double lo = std::max(a[p][0], c[q][0]), hi = std::min(a[p][1], c[q][1]);
          if (hi > lo) inter += hi - lo;
          if (a[p][1] < c[q][1]) ++p; else ++q;
        }
        for (const auto& iv : c) clump += iv[1] - iv[0];
      }
    const double uni = shape + clump - inter;
    return uni > 0 ? inter / uni : 0.0;
  }
};

// 128 directions resolve a sphere's reach to about a tenth of its radius's cap angle; the finished
// fill is checked with a finer set (clumps_test.cpp). A weight of 10 makes a shortfall of a hundredth
// of a radius cost a tenth of IoU.
constexpr int kReachDirections = 128;
constexpr double kBurialWeight = 10.0;

// Every sphere must reach out of the union of the others by at least `margin` of its radius: a
// sphere the others cover adds no surface but can set the time step
// (solver/clump/buried_spheres.hpp). The penalty is the sum of the shortfalls, in radii: a wholly
// covered sphere costs `margin` or more, against IoU gains of a few thousandths at the end of the
// search, so no optimum keeps one; it is continuous in every parameter, as Subplex needs.
double burial_penalty(const std::vector<SphereXYZR>& s, double margin, const std::vector<Vec3>& directions) {
  double pen = 0.0;
  for (std::size_t i = 0; i < s.size(); ++i)
    pen += std::max(0.0, margin - union_reach_fraction(s, i, directions));
  return pen;
}

}  // namespace

ManualFillResult manual_fill(const Shape& shape, const ManualFillOptions& o) {
  if (o.spheres < 5 || o.spheres > 15 || o.spheres % 2 == 0)
    throw std::invalid_argument("manual fill: the sphere count must be odd, 5 to 15 (got " +
                                std::to_string(o.spheres) + ")");
  if (o.max_evaluations < 100 || o.grid < 8)
    throw std::invalid_argument("manual fill: max_evaluations >= 100 and grid >= 8 are needed");
  if (!(o.min_radius_fraction > 0.0 && o.min_radius_fraction <= 1.0) || !(o.min_protrusion >= 0.0 && o.min_protrusion < 1.0))
    throw std::invalid_argument("manual fill: min_radius_fraction must be in (0, 1] and min_protrusion in [0, 1)");
  const Aabb b = shape.bounds();
  const Vec3 semi = 0.5 * (b.hi - b.lo);
  const double a = b.hi.x();  // +x end (the hilum side)
  const double ax = semi.x(), ay = semi.y(), az = semi.z();
  const double small = std::min(ay, az), big = semi.maxCoeff();
  const Layout l = layout_for(o.spheres);
  const int np = l.params();
  std::vector<double> x(static_cast<std::size_t>(np)), lo(x.size()), hi(x.size());
  const double r_lo = o.min_radius_fraction * small, r_hi = big;
  auto set = [&](int k, double v, double l0, double h0) {
    x[static_cast<std::size_t>(k)] = std::clamp(v, l0, h0);
    lo[static_cast<std::size_t>(k)] = l0;
    hi[static_cast<std::size_t>(k)] = h0;
  };
  // Start: a big centre sphere, hilum and tail spheres near the ends of the length axis, pairs
  // spread evenly along x at half the semi-axis out. Bounds keep every centre inside the box.
  set(0, 0.0, b.lo.x(), b.hi.x());
  set(1, 0.9 * small, r_lo, r_hi);
  set(2, a - 0.35 * small, 0.0, b.hi.x());
  set(3, 0.3 * small, r_lo, r_hi);
  set(4, b.lo.x() + 0.4 * small, b.lo.x(), 0.0);
  set(5, 0.4 * small, r_lo, r_hi);
  int k = 6;
  auto pairs = [&](int count, double reach) {
    for (int i = 0; i < count; ++i, k += 3) {
      const double t = count == 1 ? 0.0 : -0.5 + static_cast<double>(i) / (count - 1);
      set(k, t * ax, b.lo.x(), b.hi.x());
      set(k + 1, 0.5 * reach, 0.0, reach);
      set(k + 2, 0.45 * std::min(small, reach), r_lo, r_hi);
    }
  };
  pairs(l.y_pairs, ay);
  pairs(l.z_pairs, az);

  const QuadrantIoU iou(shape, 0.25 * big, o.grid);
  const std::vector<Vec3> directions = fibonacci_directions(kReachDirections);
  int evals = 0;
  auto objective = [&](const std::vector<double>& p) {
    ++evals;
    const std::vector<SphereXYZR> s = spheres_from(l, p.data());
    return iou(s) - kBurialWeight * burial_penalty(s, o.min_protrusion, directions);
  };
  using Obj = decltype(objective);
  nlopt::opt opt(nlopt::LN_SBPLX, static_cast<unsigned>(np));
  opt.set_lower_bounds(lo);
  opt.set_upper_bounds(hi);
  opt.set_max_objective(
      [](const std::vector<double>& p, std::vector<double>&, void* data) {
        return (*static_cast<Obj*>(data))(p);
      },
      &objective);
  opt.set_xtol_rel(1e-7);
  // Restarts from the point reached (with a fresh simplex) while they still gain: the usual cure
  // for simplex methods stalling on a non-smooth objective.
  double best = 0.0;
  for (int round = 0; round < 8 && evals < o.max_evaluations; ++round) {
    opt.set_maxeval(std::max(1, o.max_evaluations - evals));
    std::vector<double> step(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) step[i] = (round == 0 ? 0.1 : 0.03) * (hi[i] - lo[i]);
    opt.set_initial_step(step);
    double got = 0.0;
    try {
      opt.optimize(x, got);
    } catch (const nlopt::roundoff_limited&) {
      got = objective(x);  // the point reached is still the best found
    }
    const bool gained = got > best + 1e-5;
    best = std::max(best, got);
    if (!gained && round > 0) break;
  }
  ManualFillResult res;
  res.spheres = spheres_from(l, x.data());
  res.iou_objective = iou(res.spheres);
  res.evaluations = evals;
  res.layout = "length axis: 3 (centre, hilum, tail); y pairs: " + std::to_string(l.y_pairs) +
               "; z pairs: " + std::to_string(l.z_pairs);
  return res;
}

}  // namespace seedcal
