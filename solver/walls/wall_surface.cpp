#include "solver/walls/wall_surface.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace seedcal {
namespace {

std::int32_t index_of(std::size_t i) { return static_cast<std::int32_t>(i); }

// `n` vertices on the circle of radius r about the z axis at height z, counter-clockwise seen from
// +z, starting on +x; returns the first one's index.
std::int32_t ring(SurfaceMesh& m, double r, double z, int n) {
  const std::int32_t first = index_of(m.vertex_m.size());
  for (int k = 0; k < n; ++k) {
    const double a = 2.0 * M_PI * k / n;
    m.vertex_m.emplace_back(r * std::cos(a), r * std::sin(a), z);
  }
  return first;
}

// Two triangles a b c, a c d of the quad a b c d (its corners in order round it).
void quad(SurfaceMesh& m, std::int32_t a, std::int32_t b, std::int32_t c, std::int32_t d) {
  m.triangle.push_back({a, b, c});
  m.triangle.push_back({a, c, d});
}

// The strip between two rings of n vertices (equal angles), facing away from the axis (`outward`)
// or towards it.
void strip(SurfaceMesh& m, std::int32_t bottom, std::int32_t top, int n, bool outward) {
  for (int k = 0; k < n; ++k) {
    const std::int32_t k1 = (k + 1) % n;
    if (outward)
      quad(m, bottom + k, bottom + k1, top + k1, top + k);
    else
      quad(m, bottom + k, top + k, top + k1, bottom + k1);
  }
}

// A disc: a fan from a centre vertex at height z over the ring `rim`, facing +z (`up`) or -z.
void disc(SurfaceMesh& m, std::int32_t rim, double z, int n, bool up) {
  const std::int32_t c = index_of(m.vertex_m.size());
  m.vertex_m.emplace_back(0.0, 0.0, z);
  for (int k = 0; k < n; ++k) {
    const std::int32_t k1 = (k + 1) % n;
    if (up)
      m.triangle.push_back({c, rim + k, rim + k1});
    else
      m.triangle.push_back({c, rim + k1, rim + k});
  }
}

// The annulus between two rings at the same height, facing +z (`up`) or -z.
void annulus(SurfaceMesh& m, std::int32_t inner, std::int32_t outer, int n, bool up) {
  for (int k = 0; k < n; ++k) {
    const std::int32_t k1 = (k + 1) % n;
    if (up)
      quad(m, inner + k, outer + k, outer + k1, inner + k1);
    else
      quad(m, inner + k, inner + k1, outer + k1, outer + k);
  }
}

void check_segments(int segments) {
  if (segments < 3)
    throw std::invalid_argument("tessellate: segments = " + std::to_string(segments) + ": must be >= 3");
}

}  // namespace

double SurfaceMesh::area_m2() const {
  double a = 0.0;
  for (const auto& t : triangle) {
    const Vec3& p = vertex_m[static_cast<std::size_t>(t[0])];
    a += 0.5 * (vertex_m[static_cast<std::size_t>(t[1])] - p).cross(vertex_m[static_cast<std::size_t>(t[2])] - p).norm();
  }
  return a;
}

std::size_t SurfaceMesh::append(const SurfaceMesh& other, const Vec3& origin_m, const Quat& orientation) {
  const std::int32_t shift = index_of(vertex_m.size());
  const std::size_t first = triangle.size();
  for (const Vec3& v : other.vertex_m) vertex_m.push_back(origin_m + orientation * v);
  for (const auto& t : other.triangle) triangle.push_back({t[0] + shift, t[1] + shift, t[2] + shift});
  return first;
}

SurfaceMesh tessellate(const BoxShape& box) {
  SurfaceMesh m;
  for (const Rectangle& f : box.faces()) {
    const std::int32_t a = index_of(m.vertex_m.size());
    const Vec3 u = f.hu * f.u, v = f.hv * f.v;
    // Counter-clockwise seen from the side n = u x v points to.
    m.vertex_m.insert(m.vertex_m.end(), {f.centre - u - v, f.centre + u - v, f.centre + u + v, f.centre - u + v});
    quad(m, a, a + 1, a + 2, a + 3);
  }
  return m;
}

SurfaceMesh tessellate(const CylinderShape& cylinder, int segments) {
  check_segments(segments);
  SurfaceMesh m;
  const double r = cylinder.radius_m(), l = cylinder.length_m();
  const std::int32_t bottom = ring(m, r, 0.0, segments), top = ring(m, r, l, segments);
  strip(m, bottom, top, segments, true);
  if (cylinder.cap_bottom()) disc(m, bottom, 0.0, segments, false);
  if (cylinder.cap_top()) disc(m, top, l, segments, true);
  return m;
}

SurfaceMesh tessellate(const TubeShape& tube, int segments) {
  check_segments(segments);
  SurfaceMesh m;
  const double ri = tube.inner_radius_m(), ro = tube.outer_radius_m(), l = tube.length_m();
  const std::int32_t ob = ring(m, ro, 0.0, segments), ot = ring(m, ro, l, segments);
  strip(m, ob, ot, segments, true);
  if (ri > 0.0) {
    const std::int32_t ib = ring(m, ri, 0.0, segments), it = ring(m, ri, l, segments);
    strip(m, ib, it, segments, false);  // the bore faces the axis
    annulus(m, ib, ob, segments, false);
    annulus(m, it, ot, segments, true);
  } else {
    disc(m, ob, 0.0, segments, false);
    disc(m, ot, l, segments, true);
  }
  return m;
}

SurfaceMesh tessellate(const TriangleMeshShape& mesh) {
  SurfaceMesh m;
  m.vertex_m = mesh.vertices();
  m.triangle.reserve(mesh.triangle_indices().size());
  for (const auto& t : mesh.triangle_indices())
    m.triangle.push_back({index_of(t[0]), index_of(t[1]), index_of(t[2])});
  return m;
}

SurfaceMesh tessellate(const PlaneShape& plane, const Vec3& region_centre_m, double region_radius_m) {
  if (!(region_radius_m > 0.0) || !std::isfinite(region_radius_m))
    throw std::invalid_argument("tessellate: a plane's region radius = " + std::to_string(region_radius_m) +
                                ": must be finite and > 0");
  const Vec3& n = plane.normal();
  // In-plane axes: the world axis least aligned with n, made orthogonal to it (a floor, n = z,
  // gets u = x, v = y).
  const Vec3 a = std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 u = (a - a.dot(n) * n).normalized();
  const Vec3 v = n.cross(u);
  const Vec3 c = region_centre_m - region_centre_m.dot(n) * n;  // projection onto the plane
  const double h = 1.5 * region_radius_m;
  SurfaceMesh m;
  m.vertex_m = {c - h * u - h * v, c + h * u - h * v, c + h * u + h * v, c - h * u + h * v};
  quad(m, 0, 1, 2, 3);  // facing n, the particles' side
  return m;
}

SurfaceMesh tessellate(const WallShape& shape, const TessellationOptions& o) {
  if (const auto* s = dynamic_cast<const BoxShape*>(&shape)) return tessellate(*s);
  if (const auto* s = dynamic_cast<const CylinderShape*>(&shape)) return tessellate(*s, o.segments);
  if (const auto* s = dynamic_cast<const TubeShape*>(&shape)) return tessellate(*s, o.segments);
  if (const auto* s = dynamic_cast<const TriangleMeshShape*>(&shape)) return tessellate(*s);
  if (const auto* s = dynamic_cast<const PlaneShape*>(&shape))
    return tessellate(*s, o.region_centre_m, o.region_radius_m);
  throw std::logic_error(std::string("tessellate: no surface for wall shape \"") + shape.type_name() + "\"");
}

}  // namespace seedcal
