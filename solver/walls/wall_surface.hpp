#pragma once
// Wall surfaces as triangles, for drawing (the trajectory's XDMF, docs/scenes/README.md,
// "Trajectories"); the contact code never reads them. Every surface is in the wall's own frame
// (world = origin + orientation * local, as WallPose places it):
//   box       two triangles per face, the faces the shape has (an open top has five)
//   cylinder  the lateral surface as `segments` flat strips between the rim polygons at z = 0 and
//             z = length, and a fan for each cap the shape has
//   tube      the outer surface and (inner radius > 0) the bore as a cylinder's lateral surface, and
//             the two end faces as annuli between the inner and outer polygons (discs when the
//             inner radius is 0)
//   mesh      its triangles, on its welded vertices
//   plane     unbounded, so drawn as a square patch centred on the projection of a region's centre
//             onto the plane, of half-side 1.5 r, where r is the radius of a ball holding the region
//             (the spheres' bounding box): the ball's projection is a disc of radius r, so the patch
//             covers it with a margin of r / 2 on every side.
// Circles are polygons of `segments` vertices on the circle, so a disc's polygon falls short of its
// area by the factor sin(2 pi / n) / (2 pi / n) and a lateral surface by sin(pi / n) / (pi / n)
// (the inscribed polygon's area and perimeter); with 64 segments 0.16 % and 0.04 %.
#include <array>
#include <cstdint>
#include <vector>

#include "solver/walls/box_shape.hpp"
#include "solver/walls/cylinder_shape.hpp"
#include "solver/walls/mesh_shape.hpp"
#include "solver/walls/tube_shape.hpp"
#include "solver/walls/wall.hpp"

namespace seedcal {

struct SurfaceMesh {
  std::vector<Vec3> vertex_m;
  std::vector<std::array<std::int32_t, 3>> triangle;  // indices into vertex_m

  double area_m2() const;
  // Appends `other` with every vertex mapped to origin_m + orientation * vertex (a wall placed by
  // its pose); returns the index of its first triangle here.
  std::size_t append(const SurfaceMesh& other, const Vec3& origin_m = Vec3::Zero(),
                     const Quat& orientation = Quat::Identity());
};

struct TessellationOptions {
  int segments = 64;  // vertices around a circle, >= 3
  // Planes: the ball the patch must cover, in the wall's frame.
  Vec3 region_centre_m = Vec3::Zero();
  double region_radius_m = 0.5;
};

SurfaceMesh tessellate(const BoxShape& box);
SurfaceMesh tessellate(const CylinderShape& cylinder, int segments);
SurfaceMesh tessellate(const TubeShape& tube, int segments);
SurfaceMesh tessellate(const TriangleMeshShape& mesh);
SurfaceMesh tessellate(const PlaneShape& plane, const Vec3& region_centre_m, double region_radius_m);
// Any wall shape, by its type. Throws std::invalid_argument for segments < 3 or a region radius
// that is not > 0, and std::logic_error for a shape type this file does not know (a new shape
// must add its surface here).
SurfaceMesh tessellate(const WallShape& shape, const TessellationOptions& options);

}  // namespace seedcal
