#include "solver/walls/cylinder_shape.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace seedcal {

CylinderShape::CylinderShape(double radius_m, double length_m, bool inside, bool cap_bottom, bool cap_top)
    : radius_(radius_m), length_(length_m), inside_(inside), cap_bottom_(cap_bottom), cap_top_(cap_top) {
  if (!(radius_m > 0.0) || !(length_m > 0.0))
    throw std::invalid_argument("CylinderShape: radius and length must be > 0");
}

double CylinderShape::bounding_radius_m() const { return std::hypot(radius_, length_); }

bool CylinderShape::raw(int primitive, const Vec3& c, double reach, WallHit& hit, bool& rim) const {
  switch (primitive) {
    case 0: return side(c, reach, hit, rim);
    case 1: return cap_bottom_ && cap(0.0, inside_ ? 1.0 : -1.0, c, reach, hit, rim);
    case 2: return cap_top_ && cap(length_, inside_ ? -1.0 : 1.0, c, reach, hit, rim);
    default: return false;
  }
}

bool CylinderShape::nearest(int primitive, const Vec3& c, double reach, WallHit& hit) const {
  bool rim = false;
  if (!raw(primitive, c, reach, hit, rim)) return false;
  if (!rim) return true;
  // A rim contact is shared by the side and a cap: counted once (rule in wall.hpp).
  const double tol = boundary_tolerance(reach);
  WallHit other;
  bool other_rim = false;
  for (int g = 0; g < 3; ++g) {
    if (g == primitive || !raw(g, c, hit.distance + tol, other, other_rim)) continue;
    const bool same_point = (other.point - hit.point).norm() <= tol;
    if (same_point ? g < primitive : other.distance < hit.distance - tol) return false;
  }
  return true;
}

bool CylinderShape::side(const Vec3& c, double reach, WallHit& hit, bool& rim) const {
  const double rho = std::hypot(c.x(), c.y());
  const Vec3 radial = rho > 1e-300 ? Vec3(c.x() / rho, c.y() / rho, 0.0) : Vec3::UnitX();
  if (c.z() >= 0.0 && c.z() <= length_) {
    const double d = inside_ ? radius_ - rho : rho - radius_;  // signed, > 0 on the particle side
    if (std::abs(d) >= reach) return false;
    // A finite wall is a thin shell: a sphere on its back side (e.g. one that has moved out over the
    // rim of a sheared ring) touches it from there, instead of being pulled through.
    hit.distance = std::abs(d);
    hit.normal = (inside_ == (d >= 0.0)) ? radial : Vec3(-radial);
    hit.point = Vec3(radius_ * radial.x(), radius_ * radial.y(), c.z());
    rim = false;
    return true;
  }
  // Beyond the axial extent: the rim circle.
  rim = true;
  const Vec3 p(radius_ * radial.x(), radius_ * radial.y(), std::clamp(c.z(), 0.0, length_));
  return point_hit(c, p, reach, hit);
}

// A disc at z = z0; `inward` is the side particles live on (+1: z > z0).
bool CylinderShape::cap(double z0, double inward, const Vec3& c, double reach, WallHit& hit,
                        bool& rim) const {
  const double rho = std::hypot(c.x(), c.y());
  if (rho <= radius_) {
    const double d = inward * (c.z() - z0);
    if (std::abs(d) >= reach) return false;
    hit.distance = std::abs(d);  // thin shell, as the lateral surface
    hit.normal = Vec3(0.0, 0.0, d >= 0.0 ? -inward : inward);
    hit.point = Vec3(c.x(), c.y(), z0);
    rim = false;
    return true;
  }
  rim = true;
  const Vec3 p(radius_ * c.x() / rho, radius_ * c.y() / rho, z0);
  return point_hit(c, p, reach, hit);
}

}  // namespace seedcal
