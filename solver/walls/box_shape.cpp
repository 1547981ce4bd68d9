#include "solver/walls/box_shape.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace seedcal {

bool Rectangle::nearest(const Vec3& c, double reach, WallHit& hit) const {
  const Vec3 r = c - centre;
  const double a = r.dot(u), b = r.dot(v), h = r.dot(n);
  if (std::abs(a) <= hu && std::abs(b) <= hv) {
    if (std::abs(h) >= reach) return false;
    hit.distance = std::abs(h);  // a thin face: touched from either side
    hit.normal = h >= 0.0 ? Vec3(-n) : n;
    hit.point = c - h * n;
    return true;
  }
  const Vec3 p = centre + std::clamp(a, -hu, hu) * u + std::clamp(b, -hv, hv) * v;
  return point_hit(c, p, reach, hit);
}

BoxShape::BoxShape(const Vec3& s, bool open_top) {
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
}

double BoxShape::bounding_radius_m() const {
  double r = 0.0;
  for (const Rectangle& f : faces_) r = std::max(r, f.centre.norm() + std::hypot(f.hu, f.hv));
  return r;
}

}  // namespace seedcal
