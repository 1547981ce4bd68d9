#include "calibrate/clumps/seed_shape.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "solver/core/errors.hpp"
#include "solver/walls/surface_reader.hpp"

namespace seedcal {
namespace {

constexpr double kPi = std::numbers::pi;

void merge_sorted(std::vector<Interval>& v) {
  if (v.size() < 2) return;
  std::sort(v.begin(), v.end());
  std::size_t w = 0;
  for (std::size_t i = 1; i < v.size(); ++i) {
    if (v[i][0] <= v[w][1]) {
      v[w][1] = std::max(v[w][1], v[i][1]);
    } else {
      v[++w] = v[i];
    }
  }
  v.resize(w + 1);
}

double total_length(const std::vector<Interval>& v) {
  double s = 0.0;
  for (const auto& i : v) s += i[1] - i[0];
  return s;
}

// Length of the intersection of two sorted, disjoint interval lists.
double intersection_length(const std::vector<Interval>& a, const std::vector<Interval>& b) {
  double s = 0.0;
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    const double lo = std::max(a[i][0], b[j][0]), hi = std::min(a[i][1], b[j][1]);
    if (hi > lo) s += hi - lo;
    if (a[i][1] < b[j][1]) ++i; else ++j;
  }
  return s;
}

// Area of the intersection of a disk of radius rho and a concentric ellipse with semi-axes p, q:
// in polar form, 4 [rho^2 theta*/2 + (p q / 2)(pi/2 - atan((p/q) tan theta*))] where the ellipse's
// radius r_e(theta) = (cos^2/p^2 + sin^2/q^2)^(-1/2) meets rho at theta*, using
// int r_e^2 / 2 dtheta = (p q / 2) atan((p/q) tan theta).
double disk_ellipse_intersection(double rho, double p, double q) {
  if (p < q) std::swap(p, q);
  if (rho <= 0.0 || q <= 0.0) return 0.0;
  if (rho <= q) return kPi * rho * rho;
  if (rho >= p) return kPi * p * q;
  const double s2 = (1.0 / (rho * rho) - 1.0 / (p * p)) / (1.0 / (q * q) - 1.0 / (p * p));
  const double th = std::asin(std::sqrt(std::clamp(s2, 0.0, 1.0)));
  return 4.0 * (0.5 * rho * rho * th + 0.5 * p * q * (0.5 * kPi - std::atan(p / q * std::tan(th))));
}

}  // namespace

bool Shape::inside(const Vec3& p) const {
  std::vector<Interval> c;
  chords(p.y(), p.z(), c);
  for (const auto& i : c)
    if (p.x() >= i[0] && p.x() <= i[1]) return true;
  return false;
}

// ---------------------------------------------------------------------------------------------
EllipsoidShape::EllipsoidShape(const EllipsoidSpec& spec) : spec_(spec) {
  if (!(spec.length_m > 0.0) || !(spec.width_m > 0.0) || !(spec.thickness_m > 0.0))
    throw std::invalid_argument("ellipsoid: length, width and thickness must be > 0");
  if (!(spec.hilum_radius_m >= 0.0) || !(spec.hilum_centre >= 0.0 && spec.hilum_centre <= 1.0))
    throw std::invalid_argument("ellipsoid: hilum radius must be >= 0 and its centre in [0, 1]");
  semi_ = 0.5 * Vec3(spec.length_m, spec.width_m, spec.thickness_m);
  volume_ = 4.0 / 3.0 * kPi * semi_.prod();
  if (has_hilum()) {
    const double a = semi_.x(), r = spec.hilum_radius_m, xh = spec.hilum_centre * a;
    const double x0 = std::min(-a, xh - r), x1 = std::max(a, xh + r);
    // Slice area of the part of the hilum sphere outside the ellipsoid.
    auto extra = [&](double x) {
      const double e = std::max(0.0, 1.0 - (x / a) * (x / a));
      const double p = semi_.y() * std::sqrt(e), q = semi_.z() * std::sqrt(e);
      const double rho2 = r * r - (x - xh) * (x - xh);
      if (rho2 <= 0.0) return 0.0;
      const double rho = std::sqrt(rho2);
      return kPi * rho2 - disk_ellipse_intersection(rho, p, q);
    };
    constexpr int kPanels = 4000;  // composite Simpson, even
    const double hx = (x1 - x0) / kPanels;
    double s = extra(x0) + extra(x1);
    for (int i = 1; i < kPanels; ++i) s += (i % 2 ? 4.0 : 2.0) * extra(x0 + i * hx);
    volume_ += s * hx / 3.0;
  }
}

void EllipsoidShape::chords(double y, double z, std::vector<Interval>& out) const {
  out.clear();
  const double t = 1.0 - (y / semi_.y()) * (y / semi_.y()) - (z / semi_.z()) * (z / semi_.z());
  if (t > 0.0) {
    const double half = semi_.x() * std::sqrt(t);
    out.push_back({-half, half});
  }
  if (has_hilum()) {
    const double q = spec_.hilum_radius_m * spec_.hilum_radius_m - y * y - z * z;
    if (q > 0.0) {
      const double xh = spec_.hilum_centre * semi_.x(), half = std::sqrt(q);
      out.push_back({xh - half, xh + half});
      merge_sorted(out);
    }
  }
}

bool EllipsoidShape::inside(const Vec3& p) const {
  if (p.cwiseQuotient(semi_).squaredNorm() <= 1.0) return true;
  return has_hilum() && (p - hilum_centre_m()).norm() <= spec_.hilum_radius_m;
}

Aabb EllipsoidShape::bounds() const {
  Aabb b{-semi_, semi_};
  if (has_hilum()) {
    const Vec3 c = hilum_centre_m();
    b.lo = b.lo.cwiseMin(c - Vec3::Constant(spec_.hilum_radius_m));
    b.hi = b.hi.cwiseMax(c + Vec3::Constant(spec_.hilum_radius_m));
  }
  return b;
}

std::string EllipsoidShape::describe() const {
  std::ostringstream s;
  s << "ellipsoid " << spec_.length_m * 1e3 << " x " << spec_.width_m * 1e3 << " x "
    << spec_.thickness_m * 1e3 << " mm";
  if (has_hilum())
    s << " with a hilum bump r = " << spec_.hilum_radius_m * 1e3 << " mm at "
      << spec_.hilum_centre << " of the semi-length";
  return s.str();
}

// ---------------------------------------------------------------------------------------------
MeshShape::MeshShape(std::vector<std::array<Vec3, 3>> triangles, std::string source)
    : tris_(std::move(triangles)), source_(std::move(source)) {
  if (tris_.empty()) throw std::invalid_argument(source_ + ": the surface has no triangles");
  // Closed and consistently oriented: every directed edge appears once and its reverse once.
  // Vertices are matched by their exact coordinates (STL repeats them per triangle).
  using Key = std::array<double, 3>;
  std::map<std::pair<Key, Key>, int> directed;
  auto key = [](const Vec3& v) { return Key{v.x(), v.y(), v.z()}; };
  for (const auto& t : tris_) {
    for (const auto& v : t)
      if (!v.allFinite()) throw std::invalid_argument(source_ + ": a vertex is not finite");
    for (int e = 0; e < 3; ++e) ++directed[{key(t[e]), key(t[(e + 1) % 3])}];
  }
  std::size_t open = 0, twisted = 0;
  for (const auto& [edge, n] : directed) {
    const auto rev = directed.find({edge.second, edge.first});
    if (rev == directed.end()) ++open;
    else if (n != 1 || rev->second != 1) ++twisted;
  }
  if (open > 0)
    throw std::invalid_argument(source_ + ": the surface is not closed (" + std::to_string(open) +
                                " edges belong to one triangle only); a closed, watertight scan is needed");
  if (twisted > 0)
    throw std::invalid_argument(source_ + ": " + std::to_string(twisted) +
                                " edges are not shared by exactly two consistently oriented triangles");
  box_.lo = box_.hi = tris_[0][0];
  double v6 = 0.0;
  for (const auto& t : tris_) {
    for (const auto& v : t) {
      box_.lo = box_.lo.cwiseMin(v);
      box_.hi = box_.hi.cwiseMax(v);
    }
    v6 += t[0].dot(t[1].cross(t[2]));  // divergence theorem: sum of signed tetrahedra
  }
  volume_ = std::abs(v6) / 6.0;
  if (!(volume_ > 0.0)) throw std::invalid_argument(source_ + ": the surface encloses no volume");
  bins_ = std::clamp(static_cast<int>(std::sqrt(static_cast<double>(tris_.size())) / 2.0), 1, 256);
  bin_y0_ = box_.lo.y();
  bin_z0_ = box_.lo.z();
  bin_dy_ = (box_.hi.y() - box_.lo.y()) / bins_ * (1 + 1e-9) + 1e-300;
  bin_dz_ = (box_.hi.z() - box_.lo.z()) / bins_ * (1 + 1e-9) + 1e-300;
  bin_tris_.assign(static_cast<std::size_t>(bins_ * bins_), {});
  for (std::size_t k = 0; k < tris_.size(); ++k) {
    const auto& t = tris_[k];
    const double ylo = std::min({t[0].y(), t[1].y(), t[2].y()}), yhi = std::max({t[0].y(), t[1].y(), t[2].y()});
    const double zlo = std::min({t[0].z(), t[1].z(), t[2].z()}), zhi = std::max({t[0].z(), t[1].z(), t[2].z()});
    const int i0 = std::clamp(static_cast<int>((ylo - bin_y0_) / bin_dy_), 0, bins_ - 1);
    const int i1 = std::clamp(static_cast<int>((yhi - bin_y0_) / bin_dy_), 0, bins_ - 1);
    const int j0 = std::clamp(static_cast<int>((zlo - bin_z0_) / bin_dz_), 0, bins_ - 1);
    const int j1 = std::clamp(static_cast<int>((zhi - bin_z0_) / bin_dz_), 0, bins_ - 1);
    for (int i = i0; i <= i1; ++i)
      for (int j = j0; j <= j1; ++j)
        bin_tris_[static_cast<std::size_t>(i * bins_ + j)].push_back(static_cast<std::uint32_t>(k));
  }
}

void MeshShape::chords(double y, double z, std::vector<Interval>& out) const {
  out.clear();
  // A line through an edge or a vertex would be counted twice or not at all; nudging it by a
  // tiny, fixed, irrational fraction of the size makes that a measure-zero event.
  const double size = (box_.hi - box_.lo).maxCoeff();
  y += 1.2345678901e-9 * size;
  z += 2.7182818285e-9 * size;
  const int i = static_cast<int>(std::floor((y - bin_y0_) / bin_dy_));
  const int j = static_cast<int>(std::floor((z - bin_z0_) / bin_dz_));
  if (i < 0 || j < 0 || i >= bins_ || j >= bins_) return;
  std::vector<double> xs;
  for (std::uint32_t k : bin_tris_[static_cast<std::size_t>(i * bins_ + j)]) {
    const auto& t = tris_[k];
    // Barycentric coordinates of (y, z) in the triangle's (y, z) projection.
    const double y0 = t[0].y(), z0 = t[0].z();
    const double e1y = t[1].y() - y0, e1z = t[1].z() - z0, e2y = t[2].y() - y0, e2z = t[2].z() - z0;
    const double det = e1y * e2z - e2y * e1z;
    if (det == 0.0) continue;  // edge-on to the line
    const double py = y - y0, pz = z - z0;
    const double u = (py * e2z - e2y * pz) / det, v = (e1y * pz - py * e1z) / det;
    if (u < 0.0 || v < 0.0 || u + v > 1.0) continue;
    xs.push_back(t[0].x() + u * (t[1].x() - t[0].x()) + v * (t[2].x() - t[0].x()));
  }
  std::sort(xs.begin(), xs.end());
  for (std::size_t k = 0; k + 1 < xs.size(); k += 2)
    if (xs[k + 1] > xs[k]) out.push_back({xs[k], xs[k + 1]});
}

std::string MeshShape::describe() const {
  return "closed surface " + source_ + " (" + std::to_string(tris_.size()) + " triangles)";
}

MeshShape MeshShape::from_scan(const ScanSpec& spec) {
  WeldResult scan;
  try {
    scan = weld_vertices(read_surface(spec.path, spec.metres_per_unit), spec.weld_m);
  } catch (const SettingError& e) {
    throw std::invalid_argument(e.what());
  }
  std::string source = spec.path;
  if (spec.metres_per_unit != 1.0) source += " in " + unit_name(spec.metres_per_unit);
  if (scan.vertices_out < scan.vertices_in || scan.degenerate_dropped > 0)
    source += ", " + std::to_string(scan.vertices_in - scan.vertices_out) + " vertices welded";
  if (!spec.align) return MeshShape(std::move(scan.triangles), source);
  // Closed (the constructor says so naming the file) before its principal frame means anything.
  const MeshShape as_scanned(scan.triangles, source);
  const PrincipalFrame frame = principal_frame(scan.triangles);
  return MeshShape(to_frame(scan.triangles, frame), source + ", in its principal frame");
}

MeshShape MeshShape::from_stl(const std::string& path) { return from_scan(ScanSpec{path}); }

// ---------------------------------------------------------------------------------------------
void sphere_chords(const std::vector<SphereXYZR>& spheres, double y, double z,
                   std::vector<Interval>& out) {
  out.clear();
  for (const auto& s : spheres) {
    const double dy = y - s.centre_m.y(), dz = z - s.centre_m.z();
    const double q = s.radius_m * s.radius_m - dy * dy - dz * dz;
    if (q <= 0.0) continue;
    const double h = std::sqrt(q);
    out.push_back({s.centre_m.x() - h, s.centre_m.x() + h});
  }
  merge_sorted(out);
}

double Overlap::iou() const {
  const double uni = shape_m3 + clump_m3 - intersection_m3;
  return uni > 0.0 ? intersection_m3 / uni : 0.0;
}

Overlap shape_overlap(const Shape& shape, const std::vector<SphereXYZR>& spheres, int n) {
  Aabb b = shape.bounds();
  for (const auto& s : spheres) {
    b.lo = b.lo.cwiseMin(s.centre_m - Vec3::Constant(s.radius_m));
    b.hi = b.hi.cwiseMax(s.centre_m + Vec3::Constant(s.radius_m));
  }
  const double dy = (b.hi.y() - b.lo.y()) / n, dz = (b.hi.z() - b.lo.z()) / n;
  // Spheres binned by the (y, z) cells their silhouettes' boxes touch.
  std::vector<std::vector<SphereXYZR>> bins(static_cast<std::size_t>(n) * n);
  for (const auto& s : spheres) {
    const int i0 = std::clamp(static_cast<int>((s.centre_m.y() - s.radius_m - b.lo.y()) / dy), 0, n - 1);
    const int i1 = std::clamp(static_cast<int>((s.centre_m.y() + s.radius_m - b.lo.y()) / dy), 0, n - 1);
    const int j0 = std::clamp(static_cast<int>((s.centre_m.z() - s.radius_m - b.lo.z()) / dz), 0, n - 1);
    const int j1 = std::clamp(static_cast<int>((s.centre_m.z() + s.radius_m - b.lo.z()) / dz), 0, n - 1);
    for (int i = i0; i <= i1; ++i)
      for (int j = j0; j <= j1; ++j) bins[static_cast<std::size_t>(i) * n + j].push_back(s);
  }
  std::vector<Overlap> rows(static_cast<std::size_t>(n));
#pragma omp parallel for schedule(dynamic, 4)
  for (int i = 0; i < n; ++i) {
    std::vector<Interval> a, c;
    Overlap o;
    const double y = b.lo.y() + (i + 0.5) * dy;
    for (int j = 0; j < n; ++j) {
      const double z = b.lo.z() + (j + 0.5) * dz;
      shape.chords(y, z, a);
      sphere_chords(bins[static_cast<std::size_t>(i) * n + j], y, z, c);
      o.shape_m3 += total_length(a);
      o.clump_m3 += total_length(c);
      o.intersection_m3 += intersection_length(a, c);
    }
    rows[static_cast<std::size_t>(i)] = o;
  }
  Overlap out;
  for (const auto& o : rows) {  // fixed order: the same sum for any thread count
    out.shape_m3 += o.shape_m3 * dy * dz;
    out.clump_m3 += o.clump_m3 * dy * dz;
    out.intersection_m3 += o.intersection_m3 * dy * dz;
  }
  return out;
}

Overlap shape_overlap_converged(const Shape& shape, const std::vector<SphereXYZR>& spheres,
                                double rel_tol, double* iou_error) {
  Overlap prev = shape_overlap(shape, spheres, 64);
  Overlap cur = prev;
  double err = 1.0;
  for (int n = 128; n <= 1024; n *= 2) {
    cur = shape_overlap(shape, spheres, n);
    err = std::abs(cur.iou() - prev.iou());
    prev = cur;
    if (err < rel_tol * cur.iou()) break;
  }
  if (iou_error) *iou_error = err;
  return cur;
}

}  // namespace seedcal
