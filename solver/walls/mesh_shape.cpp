#include "solver/walls/mesh_shape.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <tuple>

namespace seedcal {

TriangleMeshShape::TriangleMeshShape(const std::vector<Triangle>& triangles, std::string source,
                                     double cell_m)
    : source_(std::move(source)) {
  // Weld bit-identical vertices (an STL repeats each shared vertex once per triangle).
  std::map<std::tuple<double, double, double>, std::uint32_t> index;
  for (const Triangle& t : triangles) {
    const Vec3 n = (t[1] - t[0]).cross(t[2] - t[0]);
    const double scale = std::max({(t[1] - t[0]).squaredNorm(), (t[2] - t[0]).squaredNorm(),
                                   (t[2] - t[1]).squaredNorm()});
    // Zero area, or so thin that its normal is rounding noise (|n| / longest edge^2 < 1e-12).
    if (!(n.norm() > 1e-12 * scale)) {
      ++dropped_;
      continue;
    }
    std::array<std::uint32_t, 3> ids{};
    for (std::size_t k = 0; k < 3; ++k) {
      const auto key = std::make_tuple(t[k].x(), t[k].y(), t[k].z());
      auto it = index.find(key);
      if (it == index.end()) {
        it = index.emplace(key, static_cast<std::uint32_t>(verts_.size())).first;
        verts_.push_back(t[k]);
      }
      ids[k] = it->second;
    }
    if (ids[0] == ids[1] || ids[1] == ids[2] || ids[0] == ids[2]) {
      ++dropped_;
      continue;
    }
    tri_.push_back(ids);
    normal_.push_back(n.normalized());
  }
  if (tri_.empty())
    throw std::invalid_argument(source_ + ": the mesh has no triangle of non-zero area");
  for (const Vec3& v : verts_) bounding_radius_ = std::max(bounding_radius_, v.norm());
  build_topology();
  build_grid(cell_m);
}

TriangleMeshShape TriangleMeshShape::from_stl(const std::string& path, double scale, double cell_m) {
  return TriangleMeshShape(read_stl(path, scale), path, cell_m);
}

Triangle TriangleMeshShape::triangle(int t) const {
  const auto& v = tri_[static_cast<std::size_t>(t)];
  return {verts_[v[0]], verts_[v[1]], verts_[v[2]]};
}

void TriangleMeshShape::build_topology() {
  const std::size_t nt = tri_.size(), nv = verts_.size();
  // Vertex -> triangles (CSR).
  vert_start_.assign(nv + 1, 0);
  for (const auto& t : tri_)
    for (std::uint32_t v : t) ++vert_start_[v + 1];
  for (std::size_t v = 0; v < nv; ++v) vert_start_[v + 1] += vert_start_[v];
  vert_tri_.assign(vert_start_[nv], 0);
  std::vector<std::uint32_t> fill(vert_start_.begin(), vert_start_.end() - 1);
  for (std::size_t t = 0; t < nt; ++t)
    for (std::uint32_t v : tri_[t]) vert_tri_[fill[v]++] = static_cast<std::uint32_t>(t);
  // Edge -> triangles: the triangles around one of its vertices that hold the other too.
  edge_start_.assign(3 * nt + 1, 0);
  edge_nbr_.clear();
  for (std::size_t t = 0; t < nt; ++t)
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t a = tri_[t][k], b = tri_[t][(k + 1) % 3];
      for (std::uint32_t i = vert_start_[a]; i < vert_start_[a + 1]; ++i) {
        const std::uint32_t g = vert_tri_[i];
        if (g == t) continue;
        const auto& tg = tri_[g];
        if (tg[0] == b || tg[1] == b || tg[2] == b) edge_nbr_.push_back(g);
      }
      edge_start_[3 * t + k + 1] = static_cast<std::uint32_t>(edge_nbr_.size());
    }
}

void TriangleMeshShape::build_grid(double cell_m) {
  Vec3 lo = verts_[0], hi = verts_[0];
  double mean_size = 0.0;
  for (const Vec3& v : verts_) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  for (std::size_t t = 0; t < tri_.size(); ++t) {
    const Triangle tr = triangle(static_cast<int>(t));
    const Vec3 tlo = tr[0].cwiseMin(tr[1]).cwiseMin(tr[2]), thi = tr[0].cwiseMax(tr[1]).cwiseMax(tr[2]);
    mean_size += (thi - tlo).maxCoeff();
  }
  mean_size /= static_cast<double>(tri_.size());
  const Vec3 ext = hi - lo;
  double cell = cell_m > 0.0 ? cell_m : mean_size;
  if (!(cell > 0.0)) cell = std::max(ext.maxCoeff(), 1e-9);
  // At most ~2e6 cells: a fine-meshed large rig then gets coarser cells, never a huge grid.
  auto cells_of = [&](double c) {
    double n = 1.0;
    for (int d = 0; d < 3; ++d) n *= std::floor(ext[d] / c) + 1.0;
    return n;
  };
  while (cells_of(cell) > 2e6) cell *= 1.26;
  cell_ = cell;
  grid_lo_ = lo;
  for (int d = 0; d < 3; ++d) dims_[static_cast<std::size_t>(d)] = static_cast<int>(std::floor(ext[d] / cell)) + 1;
  const std::size_t ncell = static_cast<std::size_t>(dims_[0]) * dims_[1] * dims_[2];
  // Two passes (count, fill) over each triangle's bounding box of cells.
  auto range = [&](const Vec3& a, const Vec3& b, std::array<int, 3>& i0, std::array<int, 3>& i1) {
    for (std::size_t d = 0; d < 3; ++d) {
      i0[d] = std::clamp(static_cast<int>(std::floor((a[static_cast<int>(d)] - lo[static_cast<int>(d)]) / cell)), 0, dims_[d] - 1);
      i1[d] = std::clamp(static_cast<int>(std::floor((b[static_cast<int>(d)] - lo[static_cast<int>(d)]) / cell)), 0, dims_[d] - 1);
    }
  };
  cell_start_.assign(ncell + 1, 0);
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<std::uint32_t> fill;
    if (pass == 1) {
      for (std::size_t c = 0; c < ncell; ++c) cell_start_[c + 1] += cell_start_[c];
      cell_tri_.assign(cell_start_[ncell], 0);
      fill.assign(cell_start_.begin(), cell_start_.end() - 1);
    }
    for (std::size_t t = 0; t < tri_.size(); ++t) {
      const Triangle tr = triangle(static_cast<int>(t));
      std::array<int, 3> i0{}, i1{};
      range(tr[0].cwiseMin(tr[1]).cwiseMin(tr[2]), tr[0].cwiseMax(tr[1]).cwiseMax(tr[2]), i0, i1);
      for (int k = i0[2]; k <= i1[2]; ++k)
        for (int j = i0[1]; j <= i1[1]; ++j)
          for (int i = i0[0]; i <= i1[0]; ++i) {
            const auto c = static_cast<std::size_t>((k * dims_[1] + j) * dims_[0] + i);
            if (pass == 0) ++cell_start_[c + 1];
            else cell_tri_[fill[c]++] = static_cast<std::uint32_t>(t);
          }
    }
  }
}

void TriangleMeshShape::candidates(const Vec3& c, double reach, std::vector<int>& out) const {
  out.clear();
  std::array<int, 3> i0{}, i1{};
  for (std::size_t d = 0; d < 3; ++d) {
    const int di = static_cast<int>(d);
    const double a = std::floor((c[di] - reach - grid_lo_[di]) / cell_);
    const double b = std::floor((c[di] + reach - grid_lo_[di]) / cell_);
    if (b < 0.0 || a > dims_[d] - 1) return;  // the reach misses the mesh's bounding box
    i0[d] = static_cast<int>(std::max(a, 0.0));
    i1[d] = static_cast<int>(std::min(b, static_cast<double>(dims_[d] - 1)));
  }
  for (int k = i0[2]; k <= i1[2]; ++k)
    for (int j = i0[1]; j <= i1[1]; ++j)
      for (int i = i0[0]; i <= i1[0]; ++i) {
        const auto cell = static_cast<std::size_t>((k * dims_[1] + j) * dims_[0] + i);
        for (std::uint32_t q = cell_start_[cell]; q < cell_start_[cell + 1]; ++q)
          out.push_back(static_cast<int>(cell_tri_[q]));
      }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

// Ericson, Real-Time Collision Detection (2005), 5.1.5 ClosestPtPointTriangle: the Voronoi region
// of p is found from the signs of dot products, in the order vertex a, vertex b, edge ab, vertex c,
// edge ac, edge bc, face.
Vec3 TriangleMeshShape::closest_point(int t, const Vec3& p, Feature& f) const {
  const auto& v = tri_[static_cast<std::size_t>(t)];
  const Vec3 &a = verts_[v[0]], &b = verts_[v[1]], &c = verts_[v[2]];
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) { f = Feature::vertex0; return a; }
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) { f = Feature::vertex1; return b; }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) { f = Feature::edge0; return a + (d1 / (d1 - d3)) * ab; }
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) { f = Feature::vertex2; return c; }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) { f = Feature::edge2; return a + (d2 / (d2 - d6)) * ac; }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    f = Feature::edge1;
    return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  }
  const double denom = 1.0 / (va + vb + vc);
  f = Feature::face;
  return a + ab * (vb * denom) + ac * (vc * denom);
}

bool TriangleMeshShape::near(int t, const Vec3& c, double reach) const {
  Feature f;
  return (closest_point(t, c, f) - c).squaredNorm() < reach * reach;
}

bool TriangleMeshShape::nearest(int t, const Vec3& c, double reach, WallHit& hit) const {
  Feature f;
  const Vec3 p = closest_point(t, c, f);
  const Vec3& n = normal_[static_cast<std::size_t>(t)];
  if (f == Feature::face) {
    const double h = (c - p).dot(n);  // signed height above the triangle's plane
    if (std::abs(h) >= reach) return false;
    hit.distance = std::abs(h);
    hit.normal = h >= 0.0 ? Vec3(-n) : n;
    hit.point = p;
    return true;
  }
  const Vec3 to = p - c;
  const double d = to.norm();
  if (d >= reach) return false;
  hit.distance = d;
  // A centre exactly on an edge has no direction to it: take the triangle's normal.
  hit.normal = d > 0.0 ? Vec3(to / d) : Vec3(-n);
  hit.point = p;
  // Shared edge or vertex: counted once (rule in wall.hpp and mesh_shape.hpp).
  const auto ft = static_cast<std::size_t>(t);
  const std::uint32_t* first;
  const std::uint32_t* last;
  if (f == Feature::edge0 || f == Feature::edge1 || f == Feature::edge2) {
    const std::size_t k = 3 * ft + static_cast<std::size_t>(f) - static_cast<std::size_t>(Feature::edge0);
    first = edge_nbr_.data() + edge_start_[k];
    last = edge_nbr_.data() + edge_start_[k + 1];
  } else {
    const std::uint32_t v = tri_[ft][static_cast<std::size_t>(f) - static_cast<std::size_t>(Feature::vertex0)];
    first = vert_tri_.data() + vert_start_[v];
    last = vert_tri_.data() + vert_start_[v + 1];
  }
  const double tol = boundary_tolerance(reach);
  for (const std::uint32_t* g = first; g != last; ++g) {
    if (*g == static_cast<std::uint32_t>(t)) continue;
    Feature fg;
    const Vec3 q = closest_point(static_cast<int>(*g), c, fg);
    const bool same_point = (q - p).norm() <= tol;
    if (same_point ? *g < static_cast<std::uint32_t>(t) : (q - c).norm() < d - tol) return false;
  }
  return true;
}

}  // namespace seedcal
