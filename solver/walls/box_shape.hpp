#pragma once
// Rectangles and boxes. A rectangle is a flat face centred on `centre` with in-plane unit axes u, v
// (half-extents hu, hv) and unit normal n = u x v pointing to the particles; within its outline it
// is a half-space (no tunnelling), beyond it the nearest point is on its edge or corner.
// A box is the six (or five, open at the top) inward-facing rectangles of [0, lx] x [0, ly] x
// [0, lz] in the wall frame: a container.
#include <vector>

#include "solver/walls/wall.hpp"

namespace seedcal {

struct Rectangle {
  Vec3 centre, u, v, n;
  double hu, hv;
  bool nearest(const Vec3& c, double reach, WallHit& hit) const;
};

class BoxShape final : public WallShape {
 public:
  // Inside of [0, lx] x [0, ly] x [0, lz]; `open_top` leaves out the face z = lz.
  BoxShape(const Vec3& size_m, bool open_top);
  // Any set of rectangles (one primitive each).
  explicit BoxShape(std::vector<Rectangle> faces) : faces_(std::move(faces)) {}
  int primitive_count() const override { return static_cast<int>(faces_.size()); }
  bool nearest(int primitive, const Vec3& c, double reach, WallHit& hit) const override {
    return faces_[static_cast<std::size_t>(primitive)].nearest(c, reach, hit);
  }
  const char* type_name() const override { return "box"; }
  double bounding_radius_m() const override;

 private:
  std::vector<Rectangle> faces_;
};

}  // namespace seedcal
