// Wall surfaces as triangles: each shape's area against its analytic area (exact for flat faces;
// for circles within the inscribed polygon's known shortfall, and equal to the polygon's own area
// to rounding), every vertex on the shape's surface (its distance function, where it has one, at
// 0), the faces and caps each shape has, and the plane's patch over its region.
#include <gtest/gtest.h>

#include <cmath>

#include "solver/walls/wall_surface.hpp"

namespace seedcal {
namespace {

// Sums of a few hundred products of O(0.1 m) numbers: relative rounding far below 1e-12.
constexpr double kRound = 1e-12;
constexpr int kSegments = 64;

// The inscribed regular n-gon: a disc's area is (n / 2) r^2 sin(2 pi / n), a lateral surface's
// 2 n r sin(pi / n) l (its perimeter times the length).
double polygon_disc(double r, int n) { return 0.5 * n * r * r * std::sin(2.0 * M_PI / n); }
double polygon_side(double r, double l, int n) { return 2.0 * n * r * std::sin(M_PI / n) * l; }
// The polygon's relative shortfall against the circle is 1 - sin(x) / x <= x^2 / 6, x = 2 pi / n
// for a disc (pi / n for a lateral surface, smaller).
double circle_shortfall(int n) { return std::pow(2.0 * M_PI / n, 2) / 6.0; }

// Smallest |distance| any primitive of the shape reports for a point (NaN when none reaches it).
double surface_distance(const WallShape& s, const Vec3& p, double reach) {
  double best = std::nan("");
  WallHit h;
  for (int k = 0; k < s.primitive_count(); ++k)
    if (s.nearest(k, p, reach, h) && !(std::abs(h.distance) >= best)) best = std::abs(h.distance);
  return best;
}

Vec3 centroid(const SurfaceMesh& m, std::size_t t) {
  const auto& i = m.triangle[t];
  return (m.vertex_m[static_cast<std::size_t>(i[0])] + m.vertex_m[static_cast<std::size_t>(i[1])] +
          m.vertex_m[static_cast<std::size_t>(i[2])]) / 3.0;
}

void expect_valid_indices(const SurfaceMesh& m) {
  for (const auto& t : m.triangle)
    for (const std::int32_t i : t) {
      EXPECT_GE(i, 0);
      EXPECT_LT(static_cast<std::size_t>(i), m.vertex_m.size());
    }
}

TEST(WallSurface, BoxClosedOpenAndOutside) {
  const Vec3 s(0.1, 0.2, 0.3);
  const double closed = 2.0 * (s.x() * s.y() + s.y() * s.z() + s.x() * s.z());
  for (const auto facing : {BoxShape::Facing::inside, BoxShape::Facing::outside}) {
    const SurfaceMesh c = tessellate(BoxShape(s, false, facing));
    EXPECT_EQ(c.triangle.size(), 12u);
    EXPECT_NEAR(c.area_m2(), closed, kRound * closed);
    expect_valid_indices(c);
    const SurfaceMesh o = tessellate(BoxShape(s, true, facing));
    EXPECT_EQ(o.triangle.size(), 10u);  // no lid
    EXPECT_NEAR(o.area_m2(), closed - s.x() * s.y(), kRound * closed);
  }
  // Every vertex is a corner of [0, lx] x [0, ly] x [0, lz]: each coordinate 0 or the size.
  for (const Vec3& v : tessellate(BoxShape(s, false)).vertex_m)
    for (int k = 0; k < 3; ++k)
      EXPECT_TRUE(std::abs(v[k]) < 1e-15 || std::abs(v[k] - s[k]) < 1e-15) << v.transpose();
  // One tilted plate: 4 hu hv, its corners in its plane; its triangles face n = u x v.
  const Rectangle plate = Rectangle::make(Vec3(0.1, 0.0, 0.2), Vec3(1.0, 1.0, 0.0), Vec3(0.0, 0.3, 1.0), 0.05, 0.02);
  const SurfaceMesh p = tessellate(BoxShape({plate}));
  EXPECT_NEAR(p.area_m2(), 4.0 * 0.05 * 0.02, kRound);
  for (const Vec3& v : p.vertex_m) EXPECT_NEAR((v - plate.centre).dot(plate.n), 0.0, 1e-15);
  for (std::size_t t = 0; t < p.triangle.size(); ++t) {
    const auto& i = p.triangle[t];
    const Vec3 n = (p.vertex_m[static_cast<std::size_t>(i[1])] - p.vertex_m[static_cast<std::size_t>(i[0])])
                       .cross(p.vertex_m[static_cast<std::size_t>(i[2])] - p.vertex_m[static_cast<std::size_t>(i[0])]);
    EXPECT_GT(n.dot(plate.n), 0.0);
  }
}

TEST(WallSurface, CylinderShellAndItsCaps) {
  const double r = 0.08, l = 0.05;
  const double side = polygon_side(r, l, kSegments), cap = polygon_disc(r, kSegments);
  struct Case {
    bool bottom, top;
    double polygon, analytic;
  };
  for (const Case& c : {Case{false, false, side, 2.0 * M_PI * r * l},
                         Case{true, false, side + cap, 2.0 * M_PI * r * l + M_PI * r * r},
                         Case{true, true, side + 2.0 * cap, 2.0 * M_PI * r * l + 2.0 * M_PI * r * r}}) {
    for (const bool inside : {true, false}) {
      const CylinderShape shape(r, l, inside, c.bottom, c.top);
      const SurfaceMesh m = tessellate(shape, kSegments);
      expect_valid_indices(m);
      EXPECT_EQ(m.triangle.size(), static_cast<std::size_t>(kSegments * (2 + c.bottom + c.top)));
      EXPECT_NEAR(m.area_m2(), c.polygon, kRound * c.polygon);
      EXPECT_LT(c.analytic - m.area_m2(), circle_shortfall(kSegments) * c.analytic);
      EXPECT_GT(c.analytic - m.area_m2(), 0.0);  // inscribed: always short
      // Vertices on the shell or a cap: the shape's own distance 0 (to rounding of r cos, r sin).
      for (const Vec3& v : m.vertex_m) EXPECT_LT(surface_distance(shape, v, 1e-3), 1e-15) << v.transpose();
      // A triangle's inside lies within the sagitta r (1 - cos(pi / n)) of the surface.
      const double sagitta = r * (1.0 - std::cos(M_PI / kSegments));
      for (std::size_t t = 0; t < m.triangle.size(); ++t)
        EXPECT_LE(surface_distance(shape, centroid(m, t), 1e-3), sagitta + 1e-15);
    }
  }
  EXPECT_THROW(tessellate(CylinderShape(r, l, true, true, true), 2), std::invalid_argument);
}

TEST(WallSurface, TubeRingAndSolidCylinder) {
  const double ri = 0.03, ro = 0.04, l = 0.02;
  const TubeShape ringed(ri, ro, l);
  const SurfaceMesh m = tessellate(ringed, kSegments);
  expect_valid_indices(m);
  // Outer surface, bore and the two annular ends.
  const double polygon = polygon_side(ro, l, kSegments) + polygon_side(ri, l, kSegments) +
                         2.0 * (polygon_disc(ro, kSegments) - polygon_disc(ri, kSegments));
  const double analytic = 2.0 * M_PI * (ro + ri) * l + 2.0 * M_PI * (ro * ro - ri * ri);
  EXPECT_EQ(m.triangle.size(), static_cast<std::size_t>(8 * kSegments));
  EXPECT_NEAR(m.area_m2(), polygon, kRound * polygon);
  EXPECT_LT(analytic - m.area_m2(), circle_shortfall(kSegments) * analytic);
  for (const Vec3& v : m.vertex_m) EXPECT_LT(surface_distance(ringed, v, 1e-3), 1e-15) << v.transpose();

  const TubeShape solid(0.0, ro, l);  // a piston: outer surface and two discs
  const SurfaceMesh s = tessellate(solid, kSegments);
  expect_valid_indices(s);
  const double solid_polygon = polygon_side(ro, l, kSegments) + 2.0 * polygon_disc(ro, kSegments);
  EXPECT_NEAR(s.area_m2(), solid_polygon, kRound * solid_polygon);
  for (const Vec3& v : s.vertex_m) EXPECT_LT(surface_distance(solid, v, 1e-3), 1e-15) << v.transpose();
}

TEST(WallSurface, MeshIsItsTriangles) {
  // Two triangles of a unit square in z = 0 and one standing on its edge, sharing vertices.
  const std::vector<Triangle> tris = {{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0)},
                                      {Vec3(0, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)},
                                      {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 0, 1)}};
  const TriangleMeshShape mesh(tris, "test");
  const SurfaceMesh m = tessellate(mesh);
  EXPECT_EQ(m.vertex_m.size(), 5u);  // welded
  ASSERT_EQ(m.triangle.size(), 3u);
  EXPECT_NEAR(m.area_m2(), 1.5, kRound);
  for (std::size_t t = 0; t < 3; ++t)
    for (std::size_t k = 0; k < 3; ++k)
      EXPECT_EQ(m.vertex_m[static_cast<std::size_t>(m.triangle[t][k])], mesh.triangle(static_cast<int>(t))[k]);
}

TEST(WallSurface, PlanePatchCoversItsRegion) {
  const PlaneShape floor(Vec3::UnitZ());
  const Vec3 c(0.1, 0.2, 0.3);
  const double r = 0.05;
  const SurfaceMesh m = tessellate(floor, c, r);
  ASSERT_EQ(m.vertex_m.size(), 4u);
  EXPECT_NEAR(m.area_m2(), 9.0 * r * r, kRound);  // side 2 x 1.5 r
  Vec3 mean = Vec3::Zero();
  for (const Vec3& v : m.vertex_m) {
    EXPECT_NEAR(v.z(), 0.0, 1e-15);
    EXPECT_NEAR(std::abs(v.x() - c.x()), 1.5 * r, 1e-15);  // a floor's patch is axis-aligned
    EXPECT_NEAR(std::abs(v.y() - c.y()), 1.5 * r, 1e-15);
    mean += v / 4.0;
  }
  EXPECT_TRUE(mean.isApprox(Vec3(c.x(), c.y(), 0.0), 1e-15));
  // A tilted plane: its vertices on it (the shape's distance 0), the patch centred on the
  // projection of c, and every point of the ball's projection inside the square.
  const PlaneShape tilted(Vec3(1.0, -2.0, 0.5));
  const SurfaceMesh t = tessellate(tilted, c, r);
  const Vec3 n = tilted.normal();
  const Vec3 p = c - c.dot(n) * n;
  for (const Vec3& v : t.vertex_m) EXPECT_LT(surface_distance(tilted, v, 1e-3), 1e-15);
  const Vec3 u = (t.vertex_m[1] - t.vertex_m[0]).normalized(), w = (t.vertex_m[3] - t.vertex_m[0]).normalized();
  EXPECT_NEAR(u.dot(w), 0.0, 1e-15);
  // Square, of half-side 1.5 r about p along its own axes: the disc of radius r about p (the
  // ball's projection) lies inside with a margin of r / 2.
  for (const Vec3& v : t.vertex_m) {
    EXPECT_NEAR(std::abs((v - p).dot(u)), 1.5 * r, 1e-15);
    EXPECT_NEAR(std::abs((v - p).dot(w)), 1.5 * r, 1e-15);
  }
  EXPECT_THROW(tessellate(floor, c, 0.0), std::invalid_argument);
}

TEST(WallSurface, AnyShapeByTypeAndPlacedByAPose) {
  const CylinderShape drum(0.1, 0.05, true, true, true);
  TessellationOptions o;
  o.segments = 12;
  const SurfaceMesh m = tessellate(static_cast<const WallShape&>(drum), o);
  EXPECT_EQ(m.triangle.size(), 48u);
  // Placed by a pose: a quarter turn about x and a shift; areas are kept, indices shifted.
  SurfaceMesh world;
  world.append(tessellate(BoxShape(Vec3(0.1, 0.1, 0.1), true), o));
  const std::size_t first = world.append(m, Vec3(1.0, 2.0, 3.0), Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX())));
  EXPECT_EQ(first, 10u);
  EXPECT_EQ(world.triangle[first][0], m.triangle[0][0] + 20);
  EXPECT_NEAR(world.area_m2(), 0.05 + m.area_m2(), kRound);
  // Vertex (r, 0, l) of the drum goes to (1 + r, 2 - l, 3).
  EXPECT_TRUE(world.vertex_m[20 + 12].isApprox(Vec3(1.1, 1.95, 3.0), 1e-15));

  struct Odd final : WallShape {
    int primitive_count() const override { return 0; }
    bool nearest(int, const Vec3&, double, WallHit&) const override { return false; }
    const char* type_name() const override { return "odd"; }
    double bounding_radius_m() const override { return 0.0; }
  };
  EXPECT_THROW(tessellate(Odd(), o), std::logic_error);
}

}  // namespace
}  // namespace seedcal
