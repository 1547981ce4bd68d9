#pragma once
// A finite circular cylinder about the wall frame's z axis, from z = 0 to z = length_m, radius
// radius_m. `inside`: particles live inside (a drum, a shear-box ring, a piling tube); otherwise
// outside. Optional end caps (discs of the same radius) at z = 0 and z = length_m.
// Primitives: 0 = lateral surface, 1 = cap at z = 0, 2 = cap at z = length_m.
//
// Nearest points: a finite wall is a thin shell. Within the axial extent the lateral surface is
// touched from whichever side the sphere centre is on (a sheared ring's rim must not pull in a
// sphere that sits outside it); beyond it the nearest point is on the rim circle. A cap likewise
// within its radius, its rim beyond. (Infinite planes, by contrast, are half-spaces.) A sphere
// would need to cross a whole radius in one step to tunnel through a shell. Where a cap meets the
// side, a sphere beyond both (outside a closed can, by its rim) gets one rim contact, by the rule
// in wall.hpp. The symmetry axis is z: a drum turning about its axis moves no surface point, so it
// never forces a neighbour-list rebuild (surface_displacement_m).
#include "solver/walls/wall.hpp"

namespace seedcal {

class CylinderShape final : public WallShape {
 public:
  CylinderShape(double radius_m, double length_m, bool inside, bool cap_bottom, bool cap_top);
  int primitive_count() const override { return 3; }
  bool nearest(int primitive, const Vec3& c, double reach, WallHit& hit) const override;
  bool near(int primitive, const Vec3& c, double reach) const override {
    WallHit hit;
    bool rim = false;
    return raw(primitive, c, reach, hit, rim);
  }
  const char* type_name() const override { return "cylinder"; }
  double bounding_radius_m() const override;
  Vec3 symmetry_axis() const override { return Vec3::UnitZ(); }
  double radius_m() const { return radius_; }
  double length_m() const { return length_; }
  bool inside() const { return inside_; }
  bool cap_bottom() const { return cap_bottom_; }
  bool cap_top() const { return cap_top_; }

 private:
  // Nearest point of one primitive before the shared-rim rule; `rim`: the point is on a rim.
  bool raw(int primitive, const Vec3& c, double reach, WallHit& hit, bool& rim) const;
  bool side(const Vec3& c, double reach, WallHit& hit, bool& rim) const;
  bool cap(double z0, double inward, const Vec3& c, double reach, WallHit& hit, bool& rim) const;
  double radius_, length_;
  bool inside_, cap_bottom_, cap_top_;
};

}  // namespace seedcal
