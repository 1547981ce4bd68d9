#pragma once
// A solid tube: the body between radii inner_radius_m and outer_radius_m about the wall frame's z
// axis, from z = 0 to z = length_m, with flat annular end faces. Particles live outside the solid:
// in its bore (a shear-box ring of real wall thickness) or around it. With inner_radius_m = 0 it is
// a solid cylinder (a loading cap, a piston).
//
// Nearest point. The solid is a body of revolution whose meridian section is the rectangle
// [inner, outer] x [0, length] in (rho, z). For a sphere centre at (rho, theta, z) the nearest
// surface point lies in the same meridian half-plane: the point of the rectangle nearest to
// (rho, z), i.e. (rho, z) clamped into it. Inside a face's span that is the face (the bore, the outer
// surface, an end face); beyond a corner it is the corner's circle (a ring's edge), so the normal
// turns smoothly from the bore to the end face over the edge and a sphere sliding over the edge
// keeps one contact and its history. A centre inside the solid (a sphere pushed through more than
// its radius) is pushed out through the nearest face. One primitive: a convex section gives one
// nearest point, so one contact per sphere. On the axis of a bore (rho = 0 < inner) every bore
// point is equally near; the +x side is taken (a sphere as wide as the bore, never a seed in a ring).
//
// Unlike CylinderShape, a thin shell with open rims, the end faces are real surfaces: a shear box's
// two rings cover the crescents that open between them as the upper ring moves (the ZJ apparatus,
// docs/scenes/direct_shear.md), and seeds cannot climb over a rim.
#include "solver/walls/wall.hpp"

namespace seedcal {

class TubeShape final : public WallShape {
 public:
  TubeShape(double inner_radius_m, double outer_radius_m, double length_m);
  int primitive_count() const override { return 1; }
  bool nearest(int primitive, const Vec3& c, double reach, WallHit& hit) const override;
  const char* type_name() const override { return "tube"; }
  double bounding_radius_m() const override;
  Vec3 symmetry_axis() const override { return Vec3::UnitZ(); }
  double inner_radius_m() const { return inner_; }
  double outer_radius_m() const { return outer_; }
  double length_m() const { return length_; }

 private:
  double inner_, outer_, length_;
};

}  // namespace seedcal
