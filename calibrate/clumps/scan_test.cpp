// Scans as users have them (scan.hpp): vertices that differ in their last digits weld into a closed
// surface, and a box scanned in any pose turns into its principal frame with the analytic second
// moments of a box (int x^2 dV = V a^2 / 12 for edge a), its length along x.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <fstream>
#include <stdexcept>

#include "calibrate/clumps/scan.hpp"
#include "calibrate/clumps/seed_shape.hpp"

namespace seedcal {
namespace {

// A box of edges a, b, c centred at the origin, as 12 outward triangles, every triangle with its own
// copies of its vertices (as STL writes them), then turned by `r` and moved by `t`.
std::vector<Triangle> box(double a, double b, double c, const Mat3& r = Mat3::Identity(), const Vec3& t = Vec3::Zero()) {
  auto p = [&](int i, int j, int k) { return Vec3(r * Vec3((i - 0.5) * a, (j - 0.5) * b, (k - 0.5) * c) + t); };
  const int q[6][4][3] = {{{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}}, {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}},
                          {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}}, {{1, 1, 0}, {0, 1, 0}, {0, 1, 1}, {1, 1, 1}},
                          {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}}, {{0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {0, 1, 0}}};
  std::vector<Triangle> tris;
  for (const auto& f : q) {
    const Vec3 v0 = p(f[0][0], f[0][1], f[0][2]), v1 = p(f[1][0], f[1][1], f[1][2]);
    const Vec3 v2 = p(f[2][0], f[2][1], f[2][2]), v3 = p(f[3][0], f[3][1], f[3][2]);
    tris.push_back({v0, v1, v2});
    tris.push_back({v0, v2, v3});
  }
  return tris;
}

Mat3 turn() {
  return (Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()) * Eigen::AngleAxisd(-1.1, Vec3::UnitZ())).toRotationMatrix();
}

TEST(Scan, WeldingClosesASurfaceWhoseCopiesDiffer) {
  std::vector<Triangle> tris = box(8e-3, 4e-3, 3e-3);
  // Every copy of a vertex a few nanometres off, as float round-off in a millimetre file leaves it.
  int k = 0;
  for (Triangle& t : tris)
    for (Vec3& v : t) {
      ++k;
      v += 3e-9 * Vec3(std::sin(k), std::cos(3 * k), std::sin(7 * k));
    }
  EXPECT_THROW(MeshShape(tris, "jittered"), std::invalid_argument);  // the open-mesh error
  const WeldResult w = weld_vertices(tris, 1e-6);
  EXPECT_EQ(w.vertices_in, 36u);
  EXPECT_EQ(w.vertices_out, 8u);
  EXPECT_EQ(w.degenerate_dropped, 0u);
  const MeshShape m(w.triangles, "welded");
  EXPECT_NEAR(m.volume_m3(), 8e-3 * 4e-3 * 3e-3, 1e-6 * 9.6e-8);
  // Exact copies weld with no tolerance; a triangle whose two corners weld into one is dropped.
  EXPECT_EQ(weld_vertices(box(1, 1, 1), 0.0).vertices_out, 8u);
  const std::vector<Triangle> sliver = {{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1e-9, 0)}};
  const WeldResult s = weld_vertices(sliver, 1e-6);
  EXPECT_EQ(s.degenerate_dropped, 1u);
  EXPECT_TRUE(s.triangles.empty());
}

// A box in any pose: its principal frame puts the centroid at the origin, the longest edge on x,
// the shortest on z, with the second moments of a box, whichever way the surface is oriented.
TEST(Scan, PrincipalFrameOfAScannedBox) {
  const double a = 8e-3, b = 4e-3, c = 3e-3, v = a * b * c;
  for (const bool inward : {false, true}) {
    std::vector<Triangle> tris = box(a, b, c, turn(), Vec3(0.1, -0.2, 0.05));
    if (inward)
      for (Triangle& t : tris) std::swap(t[1], t[2]);
    const PrincipalFrame f = principal_frame(tris);
    EXPECT_NEAR(f.volume_m3, v, 1e-12 * v);
    EXPECT_NEAR((f.centroid_m - Vec3(0.1, -0.2, 0.05)).norm(), 0.0, 1e-12);
    EXPECT_NEAR(f.second_moments_m5[0], v * a * a / 12, 1e-9 * v * a * a);
    EXPECT_NEAR(f.second_moments_m5[1], v * b * b / 12, 1e-9 * v * a * a);
    EXPECT_NEAR(f.second_moments_m5[2], v * c * c / 12, 1e-9 * v * a * a);
    EXPECT_NEAR(f.axes.determinant(), 1.0, 1e-12);
    Vec3 lo = Vec3::Constant(1.0), hi = Vec3::Constant(-1.0);
    for (const Triangle& t : to_frame(tris, f))
      for (const Vec3& p : t) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
      }
    EXPECT_NEAR(hi.x() - lo.x(), a, 1e-12);
    EXPECT_NEAR(hi.y() - lo.y(), b, 1e-12);
    EXPECT_NEAR(hi.z() - lo.z(), c, 1e-12);
    EXPECT_NEAR(hi.x() + lo.x(), 0.0, 1e-12);
  }
}

// A box with a pyramid on one end: the length axis points to the end the surface reaches farther
// from the centroid (the apex), whatever the pose.
TEST(Scan, LengthAxisPointsToTheFartherEnd) {
  const Mat3 r = turn();
  const Vec3 t(0.01, 0.02, -0.03);
  std::vector<Triangle> tris;
  for (const Triangle& tri : box(4e-3, 2e-3, 1.5e-3, r, t)) {
    // Drop the +x face (its two triangles), then close it with a pyramid.
    bool on_plus_x = true;
    for (const Vec3& p : tri) on_plus_x &= std::abs((r.transpose() * (p - t)).x() - 2e-3) < 1e-12;
    if (!on_plus_x) tris.push_back(tri);
  }
  auto p = [&](double x, double y, double z) { return Vec3(r * Vec3(x, y, z) + t); };
  const Vec3 apex = p(5e-3, 0, 0);
  const Vec3 c00 = p(2e-3, -1e-3, -0.75e-3), c10 = p(2e-3, 1e-3, -0.75e-3), c11 = p(2e-3, 1e-3, 0.75e-3),
             c01 = p(2e-3, -1e-3, 0.75e-3);
  for (const auto& [u, w] : {std::pair{c00, c10}, std::pair{c10, c11}, std::pair{c11, c01}, std::pair{c01, c00}})
    tris.push_back({u, w, apex});
  const WeldResult welded = weld_vertices(tris, 1e-9);
  const MeshShape closed(welded.triangles, "box and pyramid");  // closed and consistently oriented
  const PrincipalFrame f = principal_frame(welded.triangles);
  EXPECT_GT(f.axes.col(0).dot(r * Vec3::UnitX()), 0.999);  // along the box's +x, towards the apex
}

TEST(Scan, UnitsAndAScanFromAFile) {
  EXPECT_EQ(metres_per_unit("m"), 1.0);
  EXPECT_EQ(metres_per_unit("mm"), 1e-3);
  EXPECT_THROW(metres_per_unit("in"), std::invalid_argument);
  // A turned box written in millimetres, with per-face vertex copies a micrometre's thousandth
  // apart, as an export may have them.
  const std::string path = ::testing::TempDir() + "seedcal_scan_box.obj";
  {
    std::ofstream o(path);
    o.precision(12);
    int n = 0;
    for (const Triangle& tri : box(8, 4, 3, turn(), Vec3(20, 30, 40))) {
      for (const Vec3& v : tri) {
        const Vec3 w = v + 1e-6 * Vec3(std::sin(n + 1.0), std::cos(2.0 * n), 0.5);
        o << "v " << w.x() << " " << w.y() << " " << w.z() << "\n";
      }
      o << "f " << n + 1 << " " << n + 2 << " " << n + 3 << "\n";
      n += 3;
    }
  }
  const MeshShape m = MeshShape::from_scan({path, 1e-3, 1e-7, true});
  // The copies are welded onto the first of each, at most d = 1.5e-9 m off the box's corner: the
  // volume moves by at most about d x area (1.36e-4 m2) = 2e-13 m3, the edges by 2 d.
  EXPECT_NEAR(m.volume_m3(), 96e-9, 4e-13);
  const Aabb bb = m.bounds();
  EXPECT_NEAR(bb.hi.x() - bb.lo.x(), 8e-3, 5e-9);
  EXPECT_NEAR(bb.hi.y() - bb.lo.y(), 4e-3, 5e-9);
  EXPECT_NEAR(bb.hi.z() - bb.lo.z(), 3e-3, 5e-9);
  EXPECT_NE(m.describe().find("in mm"), std::string::npos) << m.describe();
  EXPECT_NE(m.describe().find("28 vertices welded"), std::string::npos) << m.describe();
  EXPECT_NE(m.describe().find("principal frame"), std::string::npos) << m.describe();
  // Without welding the copies do not match: the open-mesh error, naming the file.
  try {
    MeshShape::from_scan({path, 1e-3, 0.0, true});
    ADD_FAILURE() << "an unwelded scan was taken as closed";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("not closed"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace seedcal
