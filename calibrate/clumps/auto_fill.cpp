// Automatic filling: the shape is voxelised (exact chords along x, so a voxel is inside when its
// centre is), a Euclidean distance transform gives every inside voxel its distance to the surface,
// and spheres are placed greedily from the deepest voxel outwards, each as large as fits (its
// radius the centre's distance to the surface), skipping centres already inside a placed sphere,
// down to a smallest radius r_min. This is the distance-transform clump generator of Angelidakis
// et al. (CLUMP, SoftwareX 2021, "Euclidean" method, after Taghavi 2011) with the stop rule being
// the smallest radius; r_min is what the smoothness control sets: small r_min, many small
// spheres hugging the surface; large r_min, few.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "calibrate/clumps/fill.hpp"

namespace seedcal {
namespace {

struct Grid {
  Vec3 origin;  // centre of voxel (0, 0, 0)
  double h = 0.0;
  int nx = 0, ny = 0, nz = 0;
  std::vector<float> dist_m;  // inside: distance from the centre to the surface (> 0); outside: 0
  std::size_t idx(int i, int j, int k) const {
    return (static_cast<std::size_t>(k) * ny + j) * nx + i;
  }
  Vec3 centre(int i, int j, int k) const { return origin + h * Vec3(i, j, k); }
};

// 1D squared-distance transform of Felzenszwalb & Huttenlocher (Theory of Computing 8, 2012):
// d[q] = min_p (q - p)^2 + f[p], by the lower envelope of parabolas.
void dt1d(const std::vector<double>& f, std::vector<double>& d, std::vector<int>& v,
          std::vector<double>& z) {
  const int n = static_cast<int>(f.size());
  constexpr double inf = std::numeric_limits<double>::infinity();
  int k = 0;
  v[0] = 0;
  z[0] = -inf;
  z[1] = inf;
  for (int q = 1; q < n; ++q) {
    if (f[q] == inf) continue;
    if (f[v[k]] == inf) {  // no finite parabola yet
      v[k] = q;
      continue;
    }
    double s = ((f[q] + q * q) - (f[v[k]] + v[k] * v[k])) / (2.0 * q - 2.0 * v[k]);
    while (s <= z[k]) {
      --k;
      s = ((f[q] + q * q) - (f[v[k]] + v[k] * v[k])) / (2.0 * q - 2.0 * v[k]);
    }
    ++k;
    v[k] = q;
    z[k] = s;
    z[k + 1] = inf;
  }
  k = 0;
  for (int q = 0; q < n; ++q) {
    while (z[k + 1] < q) ++k;
    const double dq = q - v[k];
    d[q] = f[v[k]] == inf ? inf : dq * dq + f[v[k]];
  }
}

Grid voxelise(const Shape& shape, int voxels) {
  const Aabb b = shape.bounds();
  const Vec3 ext = b.hi - b.lo;
  Grid g;
  g.h = ext.maxCoeff() / voxels;
  // One ring of outside voxels around the box, so every inside voxel has an outside one.
  g.nx = static_cast<int>(std::ceil(ext.x() / g.h)) + 2;
  g.ny = static_cast<int>(std::ceil(ext.y() / g.h)) + 2;
  g.nz = static_cast<int>(std::ceil(ext.z() / g.h)) + 2;
  const Vec3 mid = 0.5 * (b.lo + b.hi);
  g.origin = mid - 0.5 * g.h * Vec3(g.nx - 1, g.ny - 1, g.nz - 1);
  constexpr double inf = std::numeric_limits<double>::infinity();
  std::vector<double> sq(static_cast<std::size_t>(g.nx) * g.ny * g.nz, 0.0);
#pragma omp parallel for schedule(dynamic, 2)
  for (int k = 0; k < g.nz; ++k) {
    std::vector<Interval> ch;
    for (int j = 0; j < g.ny; ++j) {
      shape.chords(g.origin.y() + j * g.h, g.origin.z() + k * g.h, ch);
      for (const auto& c : ch) {
        const int i0 = std::max(0, static_cast<int>(std::ceil((c[0] - g.origin.x()) / g.h)));
        const int i1 = std::min(g.nx - 1, static_cast<int>(std::floor((c[1] - g.origin.x()) / g.h)));
        for (int i = i0; i <= i1; ++i) sq[g.idx(i, j, k)] = inf;
      }
    }
  }
  // Separable exact EDT: squared distance (voxel units) from each inside centre to the nearest
  // outside centre, one axis at a time.
  auto pass = [&](int n, int m1, int m2, auto index) {
#pragma omp parallel for schedule(static)
    for (int b2 = 0; b2 < m2; ++b2) {
      std::vector<double> f(static_cast<std::size_t>(n)), d(static_cast<std::size_t>(n)),
          z(static_cast<std::size_t>(n) + 1);
      std::vector<int> v(static_cast<std::size_t>(n));
      for (int b1 = 0; b1 < m1; ++b1) {
        for (int q = 0; q < n; ++q) f[q] = sq[index(q, b1, b2)];
        dt1d(f, d, v, z);
        for (int q = 0; q < n; ++q) sq[index(q, b1, b2)] = d[q];
      }
    }
  };
  pass(g.nx, g.ny, g.nz, [&](int q, int a, int c) { return g.idx(q, a, c); });
  pass(g.ny, g.nx, g.nz, [&](int q, int a, int c) { return g.idx(a, q, c); });
  pass(g.nz, g.nx, g.ny, [&](int q, int a, int c) { return g.idx(a, c, q); });
  // The surface lies between an inside and an outside centre: on average half a voxel short of
  // the outside centre, so distance to the surface ~ sqrt(sq) h - h/2 (error below h/2).
  g.dist_m.resize(sq.size());
  for (std::size_t i = 0; i < sq.size(); ++i)
    g.dist_m[i] = sq[i] > 0.0 ? static_cast<float>(std::max(0.0, (std::sqrt(sq[i]) - 0.5) * g.h)) : 0.0f;
  return g;
}

struct Candidate {
  float d;
  std::uint32_t i;
};

std::vector<SphereXYZR> greedy(const Grid& g, const std::vector<Candidate>& sorted, double r_min,
                               double protrusion) {
  std::vector<std::uint8_t> covered(g.dist_m.size(), 0);
  std::vector<SphereXYZR> out;
  const auto nxy = static_cast<std::size_t>(g.nx) * g.ny;
  for (const Candidate& c : sorted) {
    if (c.d < r_min && !out.empty()) break;  // at least the deepest sphere
    if (covered[c.i]) continue;
    const int k = static_cast<int>(c.i / nxy), j = static_cast<int>((c.i % nxy) / g.nx),
              i = static_cast<int>(c.i % g.nx);
    const double r = c.d + protrusion * r_min;
    out.push_back({g.centre(i, j, k), r});
    // Mark the voxels inside the new sphere that could still be a centre (d >= r_min).
    const int w = static_cast<int>(std::floor(r / g.h));
    const double r2 = (r / g.h) * (r / g.h);
    for (int dk = -w; dk <= w; ++dk) {
      const int kk = k + dk;
      if (kk < 0 || kk >= g.nz) continue;
      for (int dj = -w; dj <= w; ++dj) {
        const int jj = j + dj;
        if (jj < 0 || jj >= g.ny) continue;
        const double rem = r2 - dk * dk - dj * dj;
        if (rem < 0.0) continue;
        const int wi = static_cast<int>(std::floor(std::sqrt(rem)));
        const std::size_t row = g.idx(0, jj, kk);
        for (int ii = std::max(0, i - wi); ii <= std::min(g.nx - 1, i + wi); ++ii) covered[row + ii] = 1;
      }
    }
  }
  return out;
}

double equivalent_radius(const Shape& shape) {
  return std::cbrt(3.0 * shape.volume_m3() / (4.0 * std::numbers::pi));
}

}  // namespace

double smoothness_min_radius(const Shape& shape, double smoothness) {
  return equivalent_radius(shape) * 0.0223 * std::pow(2.05, smoothness);
}

AutoFillResult auto_fill(const Shape& shape, const AutoFillOptions& o) {
  const bool by_smoothness = o.smoothness >= 0.0;
  if (by_smoothness == (o.target_spheres > 0))
    throw std::invalid_argument("auto fill: give either a smoothness or a sphere count, not both");
  if (by_smoothness && !(o.smoothness <= 5.0))
    throw std::invalid_argument("auto fill: smoothness must be in [0, 5]");
  if (!by_smoothness && o.target_spheres > 5000)
    throw std::invalid_argument("auto fill: sphere count must be in [1, 5000]");
  if (o.voxels < 32 || o.voxels > 400)
    throw std::invalid_argument("auto fill: voxels must be in [32, 400]");
  const Grid g = voxelise(shape, o.voxels);
  std::vector<Candidate> cand;
  for (std::size_t i = 0; i < g.dist_m.size(); ++i)
    if (g.dist_m[i] > 0.0f) cand.push_back({g.dist_m[i], static_cast<std::uint32_t>(i)});
  // Deepest first; ties by voxel index, so the order (and the fill) is deterministic.
  std::sort(cand.begin(), cand.end(), [](const Candidate& a, const Candidate& b) {
    return a.d != b.d ? a.d > b.d : a.i < b.i;
  });
  if (cand.empty()) throw std::invalid_argument("auto fill: the shape is thinner than a voxel");
  AutoFillResult res;
  res.voxel_m = g.h;
  if (by_smoothness) {
    // Never below one voxel: smaller spheres than the grid can resolve would only be noise.
    res.min_radius_m = std::max({smoothness_min_radius(shape, o.smoothness), g.h, o.min_radius_floor_m});
    res.spheres = greedy(g, cand, res.min_radius_m, o.protrusion);
  } else {
    // The count falls as r_min grows (not strictly: bisection on log r_min, keeping the fill whose
    // count is nearest the target, the larger r_min on ties).
    double lo = std::log(std::max(g.h, o.min_radius_floor_m)), hi = std::log(static_cast<double>(cand.front().d));
    if (hi < lo) hi = lo;  // a floor above the deepest point: one sphere
    std::vector<SphereXYZR> best;
    double best_r = 0.0;
    auto consider = [&](double r) {
      auto s = greedy(g, cand, r, o.protrusion);
      const long n = static_cast<long>(s.size());
      const long diff = std::labs(n - o.target_spheres);
      const long best_diff = std::labs(static_cast<long>(best.size()) - o.target_spheres);
      if (best.empty() || diff < best_diff || (diff == best_diff && r > best_r)) {
        best = std::move(s);
        best_r = r;
      }
      return n;
    };
    consider(std::exp(hi));
    for (int it = 0; it < 40 && static_cast<long>(best.size()) != o.target_spheres; ++it) {
      const double mid = 0.5 * (lo + hi);
      if (consider(std::exp(mid)) > o.target_spheres) lo = mid; else hi = mid;
      if (hi - lo < 1e-5) break;
    }
    res.spheres = std::move(best);
    res.min_radius_m = best_r;
  }
  return res;
}

}  // namespace seedcal
