// Triangle-mesh walls: Ericson's nearest point on a triangle against brute force, one contact per
// shared edge or vertex (flat sheets, ridges, valleys, a meshed cube against the analytic box),
// and the grid's candidate search against testing every triangle.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "solver/walls/box_shape.hpp"
#include "solver/walls/mesh_shape.hpp"

namespace seedcal {
namespace {

int contacts(const WallShape& s, const Vec3& c, double r, WallHit* first = nullptr) {
  int n = 0;
  WallHit h;
  std::vector<int> cand;
  s.candidates(c, r, cand);
  for (int p : cand)
    if (s.nearest(p, c, r, h) && h.distance < r) {
      if (n == 0 && first) *first = h;
      ++n;
    }
  return n;
}

// A flat sheet in z = 0 of nx x ny squares of side a, each split into two triangles.
std::vector<Triangle> sheet(int nx, int ny, double a) {
  std::vector<Triangle> t;
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j) {
      const Vec3 p00(i * a, j * a, 0), p10((i + 1) * a, j * a, 0), p01(i * a, (j + 1) * a, 0),
          p11((i + 1) * a, (j + 1) * a, 0);
      t.push_back({p00, p10, p11});
      t.push_back({p00, p11, p01});
    }
  return t;
}

// The cube [0, s]^3 as 12 triangles.
std::vector<Triangle> cube(double s) {
  std::vector<Triangle> t;
  auto quad = [&](Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
    t.push_back({a, b, c});
    t.push_back({a, c, d});
  };
  const Vec3 p[8] = {{0, 0, 0}, {s, 0, 0}, {s, s, 0}, {0, s, 0}, {0, 0, s}, {s, 0, s}, {s, s, s}, {0, s, s}};
  quad(p[0], p[3], p[2], p[1]);
  quad(p[4], p[5], p[6], p[7]);
  quad(p[0], p[1], p[5], p[4]);
  quad(p[2], p[3], p[7], p[6]);
  quad(p[1], p[2], p[6], p[5]);
  quad(p[0], p[4], p[7], p[3]);
  return t;
}

TEST(TriangleMesh, EricsonNearestPointMatchesBruteForce) {
  const TriangleMeshShape m({{Vec3(0, 0, 0), Vec3(0.03, 0.005, 0.002), Vec3(0.01, 0.02, -0.004)}}, "tri");
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-0.02, 0.05);
  const Triangle t = m.triangle(0);
  const int n = 400;  // barycentric sampling step 1/n of the edges (< 0.1 mm)
  int features[7] = {};
  for (int trial = 0; trial < 300; ++trial) {
    const Vec3 c(u(rng), u(rng), u(rng) - 0.015);
    TriangleMeshShape::Feature f;
    const Vec3 p = m.closest_point(0, c, f);
    ++features[static_cast<int>(f)];
    double best = 1e9;
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) {
        const Vec3 q = t[0] + (t[1] - t[0]) * (double(i) / n) + (t[2] - t[0]) * (double(j) / n);
        best = std::min(best, (q - c).norm());
      }
    const double d = (p - c).norm();
    // Never farther than any sample; no nearer than the samples by more than the sample spacing
    // (longest edge / n = 0.08 mm).
    EXPECT_LE(d, best + 1e-15);
    EXPECT_GE(d, best - 0.031 / n);
  }
  for (int f = 0; f < 7; ++f) EXPECT_GT(features[f], 0) << "feature " << f << " never tested";
}

TEST(TriangleMesh, FaceEdgeVertexHits) {
  const TriangleMeshShape m({{Vec3(0, 0, 0), Vec3(0.01, 0, 0), Vec3(0, 0.01, 0)}}, "tri");
  WallHit h;
  ASSERT_TRUE(m.nearest(0, Vec3(0.002, 0.002, 0.001), 0.002, h));  // face, from above
  EXPECT_NEAR(h.distance, 0.001, 1e-15);
  EXPECT_TRUE(h.normal.isApprox(-Vec3::UnitZ(), 1e-15));
  ASSERT_TRUE(m.nearest(0, Vec3(0.002, 0.002, -0.001), 0.002, h));  // from below (two-sided)
  EXPECT_TRUE(h.normal.isApprox(Vec3::UnitZ(), 1e-15));
  ASSERT_TRUE(m.nearest(0, Vec3(0.005, -0.001, 0.001), 0.002, h));  // edge y = 0
  EXPECT_TRUE(h.point.isApprox(Vec3(0.005, 0, 0), 1e-15));
  EXPECT_NEAR(h.distance, std::sqrt(2.0) * 0.001, 1e-15);
  ASSERT_TRUE(m.nearest(0, Vec3(-0.001, -0.001, 0.001), 0.002, h));  // vertex 0
  EXPECT_TRUE(h.point.isApprox(Vec3::Zero(), 1e-15));
  EXPECT_TRUE(h.normal.isApprox(Vec3(1, 1, -1).normalized(), 1e-12));
  EXPECT_FALSE(m.nearest(0, Vec3(0.002, 0.002, 0.003), 0.002, h));
}

TEST(TriangleMesh, FlatSheetGivesOneContactEverywhere) {
  const double a = 0.004, r = 0.003;  // triangles smaller than the sphere's contact disc
  const TriangleMeshShape m(sheet(20, 20, a), "sheet");
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> u(0.02, 0.06);
  for (int trial = 0; trial < 500; ++trial) {
    Vec3 c(u(rng), u(rng), 0.8 * r);
    if (trial == 0) c = Vec3(0.04, 0.03, 0.8 * r);  // directly over a vertex (six triangles)
    if (trial == 1) c = Vec3(0.042, 0.03, 0.8 * r);  // directly over a shared edge
    if (trial == 2) c = Vec3(0.042, 0.042, 0.8 * r);  // over a diagonal edge
    WallHit h;
    ASSERT_EQ(contacts(m, c, r, &h), 1) << "at " << c.transpose();
    EXPECT_NEAR(h.distance, 0.8 * r, 1e-15);
    EXPECT_TRUE(h.normal.isApprox(-Vec3::UnitZ(), 1e-12));
  }
}

TEST(TriangleMesh, RidgeOnceValleyTwice) {
  // Two triangles folded along the y axis (the shared edge from (0,0,0) to (0,0.02,0)).
  auto fold = [](double dz) {
    return std::vector<Triangle>{{Vec3(0, 0, 0), Vec3(0, 0.02, 0), Vec3(-0.01, 0.01, dz)},
                                 {Vec3(0, 0.02, 0), Vec3(0, 0, 0), Vec3(0.01, 0.01, dz)}};
  };
  const TriangleMeshShape ridge(fold(-0.005), "ridge"), valley(fold(0.005), "valley");
  const Vec3 c(0.0, 0.008, 0.002);
  WallHit h;
  ASSERT_EQ(contacts(ridge, c, 0.003, &h), 1);  // on the crest: the shared edge, once
  EXPECT_TRUE(h.point.isApprox(Vec3(0, 0.008, 0), 1e-15));
  EXPECT_EQ(contacts(valley, Vec3(0.0, 0.008, 0.004), 0.004), 2);  // both flanks touch
  // Over one flank of the ridge, near the crest (projection 2 mm from it): that flank's face only;
  // the other flank reaches the crest within 4 mm, but the face is strictly nearer.
  EXPECT_EQ(contacts(ridge, Vec3(0.003, 0.008, 0.001), 0.004), 1);
}

TEST(TriangleMesh, MeshedCubeCountsContactsAsTheAnalyticBox) {
  const double s = 0.02;
  const TriangleMeshShape m(cube(s), "cube");
  EXPECT_EQ(m.vertex_count(), 8u);
  const BoxShape in(Vec3::Constant(s), false), out(Vec3::Constant(s), false, BoxShape::Facing::outside);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-0.004, s + 0.004);
  const double r = 0.003;
  int tested = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const Vec3 c(u(rng), u(rng), u(rng));
    const bool inside = (c.array() > 0.0).all() && (c.array() < s).all();
    const int expect = contacts(inside ? in : out, c, r);
    WallHit hm{Vec3::Zero(), 0.0, Vec3::Zero()}, hb{Vec3::Zero(), 0.0, Vec3::Zero()};
    ASSERT_EQ(contacts(m, c, r, &hm), expect) << "at " << c.transpose();
    if (expect > 0 && !inside) {  // outside a convex body: the one contact is the same point
      contacts(out, c, r, &hb);
      EXPECT_NEAR(hm.distance, hb.distance, 1e-15);
      EXPECT_TRUE(hm.point.isApprox(hb.point, 1e-12));
    }
    tested += expect > 0;
  }
  EXPECT_GT(tested, 1000);
}

TEST(TriangleMesh, GridCandidatesHoldEveryNearTriangle) {
  const TriangleMeshShape m(sheet(50, 50, 0.004), "sheet");  // 5000 triangles
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(-0.01, 0.21);
  std::vector<int> cand;
  std::size_t total = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Vec3 c(u(rng), u(rng), u(rng) * 0.02 - 0.002);
    const double reach = 0.0025;
    m.candidates(c, reach, cand);
    EXPECT_TRUE(std::is_sorted(cand.begin(), cand.end()));
    total += cand.size();
    for (int p = 0; p < m.primitive_count(); ++p) {
      if (m.near(p, c, reach)) {
        EXPECT_TRUE(std::binary_search(cand.begin(), cand.end(), p)) << p;
      }
    }
  }
  // The grid narrows 5000 triangles to a few dozen per query (a reach of 2.5 mm spans at most
  // 3 x 3 cells of 4 mm holding ~2-8 triangles each).
  EXPECT_LT(static_cast<double>(total) / 300.0, 80.0);
}

TEST(TriangleMesh, RejectsMeshesWithoutArea) {
  EXPECT_THROW(TriangleMeshShape({{Vec3::Zero(), Vec3::UnitX(), Vec3(2, 0, 0)}}, "line"),
               std::invalid_argument);
  const TriangleMeshShape m({{Vec3::Zero(), Vec3::UnitX(), Vec3(2, 0, 0)},
                             {Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY()}}, "one good");
  EXPECT_EQ(m.primitive_count(), 1);
  EXPECT_EQ(m.dropped_triangles(), 1u);
}

}  // namespace
}  // namespace seedcal
