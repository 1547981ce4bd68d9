#include "solver/walls/tube_shape.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace seedcal {

TubeShape::TubeShape(double inner_radius_m, double outer_radius_m, double length_m)
    : inner_(inner_radius_m), outer_(outer_radius_m), length_(length_m) {
  if (!(inner_radius_m >= 0.0) || !(outer_radius_m > inner_radius_m) || !(length_m > 0.0))
    throw std::invalid_argument("TubeShape: need 0 <= inner radius < outer radius and length > 0");
}

double TubeShape::bounding_radius_m() const { return std::hypot(outer_, length_); }

bool TubeShape::nearest(int, const Vec3& c, double reach, WallHit& hit) const {
  const double rho = std::hypot(c.x(), c.y());
  // The meridian half-plane's radial direction (+x on the axis, where any direction serves).
  const Vec3 radial = rho > 0.0 ? Vec3(c.x() / rho, c.y() / rho, 0.0) : Vec3::UnitX();
  const double r_near = std::clamp(rho, inner_, outer_);
  const double z_near = std::clamp(c.z(), 0.0, length_);
  const double dr = r_near - rho, dz = z_near - c.z();
  const double distance = std::hypot(dr, dz);
  if (distance == 0.0) {
    // The centre is inside the solid: out through the nearest face (a solid cylinder has no
    // bore face), at a negative distance; the normal points into the solid, as it does from a
    // centre outside.
    const double inf = std::numeric_limits<double>::infinity();
    const double to_face[4] = {inner_ > 0.0 ? rho - inner_ : inf, outer_ - rho, c.z(), length_ - c.z()};
    const int f = static_cast<int>(std::min_element(to_face, to_face + 4) - to_face);
    const Vec3 into[4] = {radial, -radial, Vec3::UnitZ(), -Vec3::UnitZ()};
    hit.distance = -to_face[f];
    hit.normal = into[f];
    hit.point = c + hit.distance * hit.normal;
    return hit.distance < reach;
  }
  if (distance >= reach) return false;
  hit.distance = distance;
  hit.normal = (dr / distance) * radial + Vec3(0.0, 0.0, dz / distance);
  hit.point = r_near * radial + Vec3(0.0, 0.0, z_near);
  return true;
}

}  // namespace seedcal
