#pragma once
// A triangle-mesh wall (an STL surface in the wall frame). Each triangle is a primitive and a thin,
// two-sided shell: a sphere touches it from whichever side its centre is on, with the normal from
// the centre to the nearest point of the triangle (Ericson, Real-Time Collision Detection, 2005,
// section 5.1.5, ClosestPtPointTriangle). A mesh wall is not a half-space: a sphere crossing a
// triangle within one step would pass through, which needs a step of a whole radius.
//
// Shared edges and vertices. Bit-identical vertices are welded, so triangles that share an edge or
// a vertex know each other. A contact whose nearest point lies on a triangle's edge or vertex is
// counted once by the rule in wall.hpp, checked against the triangles sharing that edge (or that
// vertex): dropped when one of them is strictly nearer (a sphere over a flat mesh touches the face
// it lies over, not the edges of the triangles beside it), or reaches the same point with a lower
// index (a sphere on a ridge or a convex corner: one contact). Contacts inside two faces (a valley)
// are both kept. An open edge (no neighbour) keeps its contact: the rim of an open mesh. Meshes
// whose shared vertices differ by rounding are not welded, and their seams may count twice.
//
// Contact history is per triangle (wall_contact_list.hpp): a sphere rolling from one triangle onto
// the next starts a new tangential spring, as in LIGGGHTS's mesh walls.
//
// Candidate search: a uniform grid of cells over the mesh's bounding box, each cell listing the
// triangles whose bounding boxes overlap it; candidates() returns the triangles of the cells a
// sphere's reach overlaps, so the contact list costs O(nearby triangles) per sphere.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "solver/walls/stl_reader.hpp"
#include "solver/walls/wall.hpp"

namespace seedcal {

class TriangleMeshShape final : public WallShape {
 public:
  // `triangles` in the wall frame, m. Degenerate (zero-area) triangles are dropped (counted in
  // dropped_triangles()); throws std::invalid_argument if none is left. `cell_m` sets the grid's
  // cell size (0: the mean triangle size, enlarged so the grid has at most ~2 million cells).
  TriangleMeshShape(const std::vector<Triangle>& triangles, std::string source, double cell_m = 0.0);
  // From an STL file (stl_reader.hpp), vertices multiplied by `scale` (1e-3 for a file in mm).
  static TriangleMeshShape from_stl(const std::string& path, double scale = 1.0, double cell_m = 0.0);

  int primitive_count() const override { return static_cast<int>(tri_.size()); }
  bool nearest(int primitive, const Vec3& centre, double reach, WallHit& hit) const override;
  bool near(int primitive, const Vec3& centre, double reach) const override;
  void candidates(const Vec3& centre, double reach, std::vector<int>& out) const override;
  const char* type_name() const override { return "mesh"; }
  double bounding_radius_m() const override { return bounding_radius_; }

  const std::string& source() const { return source_; }
  std::size_t vertex_count() const { return verts_.size(); }
  std::size_t dropped_triangles() const { return dropped_; }
  double cell_size_m() const { return cell_; }
  Triangle triangle(int t) const;
  // The welded vertices and each triangle's three indices into them (vertex order as read).
  const std::vector<Vec3>& vertices() const { return verts_; }
  const std::vector<std::array<std::uint32_t, 3>>& triangle_indices() const { return tri_; }

  // Where on a triangle its nearest point lies: inside, on edge k (from vertex k to k + 1), or at
  // vertex k.
  enum class Feature : std::uint8_t { face, edge0, edge1, edge2, vertex0, vertex1, vertex2 };
  // Nearest point of triangle t to p (Ericson 5.1.5) and its feature.
  Vec3 closest_point(int t, const Vec3& p, Feature& feature) const;

 private:
  std::vector<Vec3> verts_;
  std::vector<std::array<std::uint32_t, 3>> tri_;
  std::vector<Vec3> normal_;  // unit, right-handed from the vertex order
  // Triangles sharing edge k of triangle t (t excluded): edge_nbr_[edge_start_[3 t + k] ...).
  std::vector<std::uint32_t> edge_start_, edge_nbr_;
  // Triangles using vertex v: vert_tri_[vert_start_[v] ...).
  std::vector<std::uint32_t> vert_start_, vert_tri_;
  // Uniform grid: cell (i, j, k) lists cell_tri_[cell_start_[c] ...), c = (k dims_y + j) dims_x + i.
  Vec3 grid_lo_ = Vec3::Zero();
  double cell_ = 1.0;
  std::array<int, 3> dims_{1, 1, 1};
  std::vector<std::uint32_t> cell_start_, cell_tri_;
  std::string source_;
  std::size_t dropped_ = 0;
  double bounding_radius_ = 0.0;

  void build_topology();
  void build_grid(double cell_m);
};

}  // namespace seedcal
