#pragma once
// Walls: analytic or meshed surfaces with a material, a pose and a prescribed motion law.
//
// A wall's shape is described in the wall's own frame and split into primitives (a plane is one
// primitive; a box six faces; a mesh its triangles); each primitive gives at most one contact
// point per sphere, so contact history is keyed by (sphere, wall, primitive).
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "solver/core/vec.hpp"

namespace seedcal {

// Nearest point of a primitive to a sphere centre, in the wall's frame.
struct WallHit {
  Vec3 normal;      // unit vector from the sphere centre towards the wall surface
  double distance;  // signed distance from the centre to the surface; overlap = radius - distance
  Vec3 point;       // nearest surface point
};

// Contacts at boundaries shared by primitives (box edges and corners, a cylinder's rims, a mesh's
// edges and vertices) are counted once, by one rule applied inside each shape's nearest():
//   a primitive's contact at a point p on its own boundary (an edge, a rim, a vertex; never a
//   contact inside its face) is dropped when a primitive sharing that boundary is strictly nearer
//   to the centre (the sphere then lies on the neighbour's side and touches the neighbour's face,
//   of which p is part), or reaches the same point p with a lower index (the same contact).
// A face contact is always kept: two faces of a valley or a box's inner corner touch a sphere at
// two distinct points, which are two real contacts. Within `boundary_tolerance(reach)` points and
// distances count as equal (they come from different formulas, so differ by rounding).
inline double boundary_tolerance(double reach) { return 1e-9 * reach; }

// Contact with a single surface point p (an edge, a rim, a corner): fills `hit` when the sphere
// centre c is within `reach` of it.
inline bool point_hit(const Vec3& c, const Vec3& p, double reach, WallHit& hit) {
  const Vec3 to = p - c;
  const double d = to.norm();
  if (d >= reach || d <= 0.0) return false;
  hit.distance = d;
  hit.normal = to / d;
  hit.point = p;
  return true;
}

class WallShape {
 public:
  virtual ~WallShape() = default;
  virtual int primitive_count() const = 0;
  // Fills `hit` and returns true when the sphere centre is within `reach` of the primitive.
  virtual bool nearest(int primitive, const Vec3& centre, double reach, WallHit& hit) const = 0;
  // True when the primitive's surface comes within `reach` of `centre`, before the shared-boundary
  // rule above: the contact list keeps such a primitive as a candidate even when the rule drops
  // its contact now, since the sphere may move (within the skin) to where that primitive owns it.
  virtual bool near(int primitive, const Vec3& centre, double reach) const {
    WallHit hit;
    return nearest(primitive, centre, reach, hit);
  }
  // Replaces `out` with the primitives that may lie within `reach` of `centre` (wall frame), in
  // increasing order; a superset is allowed, a primitive left out is never tested. Default: all
  // of them (a few faces); a mesh answers from its spatial grid, so the contact list and the
  // particle factory cost O(nearby triangles), not O(triangles), per sphere.
  virtual void candidates(const Vec3& centre, double reach, std::vector<int>& out) const {
    (void)centre;
    (void)reach;
    out.resize(static_cast<std::size_t>(primitive_count()));
    for (int p = 0; p < primitive_count(); ++p) out[static_cast<std::size_t>(p)] = p;
  }
  virtual const char* type_name() const = 0;
  // Radius of a ball about the wall origin holding the whole shape (infinite for a plane); with
  // the rotation angle it bounds how far a surface point moves when the wall turns.
  virtual double bounding_radius_m() const = 0;
  // A unit axis (wall frame) about which the shape is rotationally symmetric, or zero: a rotation
  // about it moves no surface point (a drum turning about its axis).
  virtual Vec3 symmetry_axis() const { return Vec3::Zero(); }
};

// An infinite plane through the wall frame's origin with unit normal `normal` pointing to the side
// where particles live. It is a half-space: a sphere that has crossed it is still pushed back, so a
// fast particle cannot tunnel through.
class PlaneShape final : public WallShape {
 public:
  explicit PlaneShape(const Vec3& normal) : normal_(normal.normalized()) {}
  int primitive_count() const override { return 1; }
  bool nearest(int, const Vec3& c, double reach, WallHit& hit) const override {
    const double d = c.dot(normal_);
    if (d >= reach) return false;
    hit.normal = -normal_;
    hit.distance = d;
    hit.point = c - d * normal_;
    return true;
  }
  const char* type_name() const override { return "plane"; }
  double bounding_radius_m() const override { return std::numeric_limits<double>::infinity(); }
  Vec3 symmetry_axis() const override { return normal_; }
  const Vec3& normal() const { return normal_; }

 private:
  Vec3 normal_;
};

// Rigid-body motion of a wall: its frame's origin and orientation as functions of time.
struct WallPose {
  Vec3 origin_m = Vec3::Zero();
  Quat orientation = Quat::Identity();
  Vec3 velocity_m_s = Vec3::Zero();
  Vec3 angular_velocity_rad_s = Vec3::Zero();
};

// How far any surface point of a wall moved between two poses (a bound).
double surface_displacement_m(const WallShape& shape, const WallPose& from, const WallPose& to);

struct Wall;

// A prescribed motion law attached to a wall: it moves the wall's pose from t to t + dt. Laws may
// read the wall's accumulated force (a servo), never the scene.
class WallMotion {
 public:
  virtual ~WallMotion() = default;
  virtual void advance(Wall& wall, double t_s, double dt_s) = 0;
  // Largest speed of any wall point within `extent_m` of the wall origin, for the energy guard.
  virtual double max_speed_m_s(double extent_m) const = 0;
};

struct Wall {
  std::string name;
  std::shared_ptr<WallMotion> motion;  // null: the wall does not move
  std::shared_ptr<const WallShape> shape;
  std::uint16_t material = 0;
  WallPose pose;
  // Accumulated each step: the force the particles exert on the wall and its torque about the
  // wall frame's origin (world frame).
  Vec3 force_n = Vec3::Zero();
  Vec3 torque_n_m = Vec3::Zero();
  double contact_stiffness_n_m = 0.0;  // summed normal stiffness Sn of its contacts (servo gain)
  int contacts = 0;                    // sphere-level contacts this step

  // Velocity of the wall's material point at world position p.
  Vec3 velocity_at(const Vec3& p) const {
    return pose.velocity_m_s + pose.angular_velocity_rad_s.cross(p - pose.origin_m);
  }
};

}  // namespace seedcal
