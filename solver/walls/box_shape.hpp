#pragma once
// Rectangles and boxes. A rectangle is a flat face centred on `centre` with in-plane unit axes u, v
// (half-extents hu, hv) and unit normal n = u x v pointing to the particles. A finite wall is a
// thin shell: within its outline a sphere touches it from whichever side its centre is on (n only
// breaks the tie of a centre exactly in the plane); beyond the outline the nearest point is on its
// edge or corner and the normal runs from the centre to that point.
//
// A box is the six (or five, open at the top) faces of [0, lx] x [0, ly] x [0, lz] in the wall
// frame, one primitive each (0 floor, 1 x = 0, 2 x = lx, 3 y = 0, 4 y = ly, 5 lid), facing inwards
// (a container) or outwards (an obstacle). Edges and corners shared by two or three faces give one
// contact, by the rule in wall.hpp.
#include <vector>

#include "solver/walls/wall.hpp"

namespace seedcal {

struct Rectangle {
  Vec3 centre, u, v, n;
  double hu, hv;
  // Nearest point of the rectangle to c within `reach`; `on_boundary` (optional) is set when the
  // point lies on an edge or corner (the centre is beyond the outline).
  bool nearest(const Vec3& c, double reach, WallHit& hit, bool* on_boundary = nullptr) const;
  // A rectangle from its centre, axes and half-extents, n = u x v.
  static Rectangle make(const Vec3& centre, const Vec3& u, const Vec3& v, double hu, double hv);
};

class BoxShape final : public WallShape {
 public:
  enum class Facing { inside, outside };
  // [0, lx] x [0, ly] x [0, lz]; `open_top` leaves out the face z = lz. Facing::inside: the
  // particles are in the box (a container); outside: around it.
  BoxShape(const Vec3& size_m, bool open_top, Facing facing = Facing::inside);
  // Any set of rectangles (one primitive each), e.g. one finite plate.
  explicit BoxShape(std::vector<Rectangle> faces);
  int primitive_count() const override { return static_cast<int>(faces_.size()); }
  bool nearest(int primitive, const Vec3& c, double reach, WallHit& hit) const override;
  bool near(int primitive, const Vec3& c, double reach) const override {
    WallHit hit;
    return faces_[static_cast<std::size_t>(primitive)].nearest(c, reach, hit);
  }
  const char* type_name() const override { return "box"; }
  double bounding_radius_m() const override;
  const std::vector<Rectangle>& faces() const { return faces_; }

 private:
  std::vector<Rectangle> faces_;
};

}  // namespace seedcal
