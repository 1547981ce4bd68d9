#pragma once
// A seed's scan as a clump's target shape: the surface read in its unit (STL, PLY or OBJ;
// solver/walls/surface_reader.hpp), its vertices welded, and the solid turned into its principal
// frame, so that x is the length axis as for a measured ellipsoid (MeshShape::from_scan in
// seed_shape.hpp does the three).
//
// Welding: scanners and mesh exports repeat a vertex per triangle, and the copies can differ in
// their last digits; vertices closer than the tolerance become one (the first of them, in file
// order), and a triangle that loses an edge to the weld is dropped. Only then can the closed-mesh
// check of MeshShape match every edge with its reverse.
//
// Principal frame: the solid's centroid and second moment of volume C = int x x^T dV, both summed
// over the signed tetrahedra (origin, a, b, c) of the triangles (divergence theorem):
//   V = sum det / 6,   int x dV = sum det / 24 (a + b + c),
//   int x x^T dV = sum det / 120 (a a^T + b b^T + c c^T + s s^T),  s = a + b + c, det = a . (b x c)
// (Tonon, "Explicit exact formulas for the 3-D tetrahedron inertia tensor in terms of its vertex
// coordinates", J. Math. Stat. 1 (2005) 8-11). The eigenvectors of the central second moment, by
// decreasing eigenvalue, are the length, width and thickness axes; each points towards the side of
// the centroid where the surface reaches farther (the hilum end of a seed), the third completes a
// right-handed frame.
#include <string>
#include <vector>

#include "solver/core/vec.hpp"
#include "solver/walls/stl_reader.hpp"

namespace seedcal {

struct ScanSpec {
  std::string path;
  double metres_per_unit = 1.0;  // 1 (unit m) or 1e-3 (unit mm)
  double weld_m = 0.0;           // vertices closer than this become one
  bool align = false;            // turn the solid into its principal frame
};

// "m" -> 1, "mm" -> 1e-3; throws std::invalid_argument naming the allowed units otherwise.
double metres_per_unit(const std::string& unit);
std::string unit_name(double metres_per_unit);

struct WeldResult {
  std::vector<Triangle> triangles;
  std::size_t vertices_in = 0, vertices_out = 0;  // distinct positions before and after
  std::size_t degenerate_dropped = 0;             // triangles that lost an edge to the weld
};
WeldResult weld_vertices(const std::vector<Triangle>& triangles, double tolerance_m);

struct PrincipalFrame {
  double volume_m3 = 0.0;
  Vec3 centroid_m = Vec3::Zero();
  Mat3 axes = Mat3::Identity();  // columns: length, width, thickness axes in the file's frame
  Vec3 second_moments_m5 = Vec3::Zero();  // eigenvalues of the central int x x^T dV, decreasing
};
// Of a closed, consistently oriented surface (either orientation).
PrincipalFrame principal_frame(const std::vector<Triangle>& triangles);
// Every vertex p as axes^T (p - centroid).
std::vector<Triangle> to_frame(const std::vector<Triangle>& triangles, const PrincipalFrame& f);

}  // namespace seedcal
