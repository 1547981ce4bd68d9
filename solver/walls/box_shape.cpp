#include "solver/walls/box_shape.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace seedcal {

bool Rectangle::nearest(const Vec3& c, double reach, WallHit& hit, bool* on_boundary) const {
  const Vec3 r = c - centre;
  const double a = r.dot(u), b = r.dot(v), h = r.dot(n);
  if (std::abs(a) <= hu && std::abs(b) <= hv) {
    if (std::abs(h) >= reach) return false;
    hit.distance = std::abs(h);  // a thin face: touched from either side
    hit.normal = h >= 0.0 ? Vec3(-n) : n;
    hit.point = c - h * n;
    if (on_boundary) *on_boundary = false;
    return true;
  }
  // Beyond the outline: the nearest point is the clamped one, on an edge or a corner.
  const Vec3 p = centre + std::clamp(a, -hu, hu) * u + std::clamp(b, -hv, hv) * v;
  if (on_boundary) *on_boundary = true;
  return point_hit(c, p, reach, hit);
}

Rectangle Rectangle::make(const Vec3& centre, const Vec3& u, const Vec3& v, double hu, double hv) {
  if (!(hu > 0.0) || !(hv > 0.0)) throw std::invalid_argument("Rectangle: half-extents must be > 0");
  const Vec3 un = u.normalized();
  const Vec3 vn = (v - v.dot(un) * un).normalized();  // Gram-Schmidt: exact right angle
  return {centre, un, vn, un.cross(vn), hu, hv};
}

BoxShape::BoxShape(const Vec3& s, bool open_top, Facing facing) {
  if (!(s.minCoeff() > 0.0)) throw std::invalid_argument("BoxShape: every size must be > 0");
  const Vec3 h = 0.5 * s;
  const Vec3 X = Vec3::UnitX(), Y = Vec3::UnitY(), Z = Vec3::UnitZ();
  // Each face: normal pointing into the box, u x v = n.
  faces_.push_back({Vec3(h.x(), h.y(), 0.0), X, Y, Z, h.x(), h.y()});           // floor
  faces_.push_back({Vec3(0.0, h.y(), h.z()), Y, Z, X, h.y(), h.z()});           // x = 0
  faces_.push_back({Vec3(s.x(), h.y(), h.z()), Z, Y, -X, h.z(), h.y()});        // x = lx
  faces_.push_back({Vec3(h.x(), 0.0, h.z()), Z, X, Y, h.z(), h.x()});           // y = 0
  faces_.push_back({Vec3(h.x(), s.y(), h.z()), X, Z, -Y, h.x(), h.z()});        // y = ly
  if (!open_top) faces_.push_back({Vec3(h.x(), h.y(), s.z()), Y, X, -Z, h.y(), h.x()});  // lid
  if (facing == Facing::outside)
    for (Rectangle& f : faces_) {
      std::swap(f.u, f.v);  // keeps u x v = n with n reversed
      std::swap(f.hu, f.hv);
      f.n = -f.n;
    }
}

BoxShape::BoxShape(std::vector<Rectangle> faces) : faces_(std::move(faces)) {
  if (faces_.empty()) throw std::invalid_argument("BoxShape: needs at least one rectangle");
}

bool BoxShape::nearest(int primitive, const Vec3& c, double reach, WallHit& hit) const {
  bool boundary = false;
  if (!faces_[static_cast<std::size_t>(primitive)].nearest(c, reach, hit, &boundary)) return false;
  if (!boundary) return true;
  // An edge or corner contact: counted once (rule in wall.hpp). Faces not sharing the point are
  // either farther (kept) or, if nearer, touch the sphere on their own side of it.
  const double tol = boundary_tolerance(reach);
  WallHit other;
  for (int g = 0; g < primitive_count(); ++g) {
    if (g == primitive) continue;
    if (!faces_[static_cast<std::size_t>(g)].nearest(c, hit.distance + tol, other)) continue;
    const bool same_point = (other.point - hit.point).norm() <= tol;
    if (same_point ? g < primitive : other.distance < hit.distance - tol) return false;
  }
  return true;
}

double BoxShape::bounding_radius_m() const {
  double r = 0.0;
  for (const Rectangle& f : faces_) r = std::max(r, f.centre.norm() + std::hypot(f.hu, f.hv));
  return r;
}

}  // namespace seedcal
