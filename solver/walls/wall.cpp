#include "solver/walls/wall.hpp"

#include <cmath>

namespace seedcal {

double surface_displacement_m(const WallShape& shape, const WallPose& from, const WallPose& to) {
  const double shift = (to.origin_m - from.origin_m).norm();
  const Quat rel = from.orientation.conjugate() * to.orientation;  // in the wall frame
  Eigen::AngleAxisd aa(rel);
  double angle = std::abs(aa.angle());
  if (angle > M_PI) angle = 2.0 * M_PI - angle;
  if (angle < 1e-15) return shift;
  const Vec3 sym = shape.symmetry_axis();
  // A turn about the symmetry axis moves no surface point.
  if (!sym.isZero(0.0) && std::abs(std::abs(aa.axis().dot(sym)) - 1.0) < 1e-12) return shift;
  return shift + angle * shape.bounding_radius_m();
}

}  // namespace seedcal
