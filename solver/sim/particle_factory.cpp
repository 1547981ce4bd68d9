#include "solver/core/portable_random.hpp"
#include "solver/sim/particle_factory.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <sstream>
#include <unordered_map>

#include "solver/core/random_rotation.hpp"
#include "solver/sim/memory_estimate.hpp"
#include "solver/walls/wall_contact_list.hpp"

namespace seedcal {

BodyDef scaled_body(const BodyDef& body, double s) {
  BodyDef b = body;
  for (SphereDef& sd : b.spheres) {
    sd.offset_m *= s;
    sd.radius_m *= s;
  }
  b.mass_kg *= s * s * s;
  b.principal_inertia_kg_m2 *= std::pow(s, 5);
  return b;
}

namespace {

// Sphere centres on a hash grid with cells of the largest diameter.
class SphereGrid {
 public:
  explicit SphereGrid(double cell) : cell_(cell) {}
  void add(const Vec3& p, double r) { map_.emplace(key(p, 0, 0, 0), std::make_pair(p, r)); }
  bool overlaps(const Vec3& p, double r) const {
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto range = map_.equal_range(key(p, dx, dy, dz));
          for (auto it = range.first; it != range.second; ++it)
            if ((it->second.first - p).squaredNorm() < (it->second.second + r) * (it->second.second + r))
              return true;
        }
    return false;
  }

 private:
  std::int64_t key(const Vec3& p, int dx, int dy, int dz) const {
    const auto ix = static_cast<std::int64_t>(std::floor(p.x() / cell_)) + dx;
    const auto iy = static_cast<std::int64_t>(std::floor(p.y() / cell_)) + dy;
    const auto iz = static_cast<std::int64_t>(std::floor(p.z() / cell_)) + dz;
    return (ix * 73856093) ^ (iy * 19349663) ^ (iz * 83492791);
  }
  double cell_;
  std::unordered_multimap<std::int64_t, std::pair<Vec3, double>> map_;
};

}  // namespace

FactoryResult insert_particles(Simulation& sim, const FactorySpec& spec) {
  // Refuse up front what would not fit in memory (sim/memory_estimate.hpp): the count asked for,
  // or the mass limit in mean-sized bodies (template mass x E[s^3] of the scale distribution).
  {
    const double m = spec.scale.mean, sd = spec.scale.sd;
    const double mean_mass = spec.body.mass_kg * (m * m * m + 3.0 * m * sd * sd);
    double want = static_cast<double>(spec.count);
    const char* key = "count";
    if (spec.count == 0 && spec.total_mass_kg > 0.0 && mean_mass > 0.0) {
      want = std::ceil(spec.total_mass_kg / mean_mass);
      key = "total_mass_kg";
    }
    const double cap = 9.0e15;  // beyond 2^53 a count is not even representable
    const double bodies = std::min(cap, static_cast<double>(sim.bodies().size()) + want);
    const double spheres = std::min(cap, static_cast<double>(sim.spheres().size()) +
                                             want * static_cast<double>(spec.body.spheres.size()));
    const MemoryEstimate est = estimate_memory(
        static_cast<std::size_t>(bodies), static_cast<std::size_t>(spheres), sim.options().threads,
        sim.options().contact.rolling == RollingModel::epsd);
    std::ostringstream what;
    what.precision(3);
    what << "the particle factory asked for " << want << " bodies of "
         << spec.body.spheres.size() << " spheres";
    check_memory(est, available_memory_bytes(), key, what.str());
  }
  FactoryResult res;
  auto& rng = sim.rng();
  const ScaleDistribution& sc = spec.scale;
  double extent = 0.0, r_tpl = 0.0;
  for (const SphereDef& s : spec.body.spheres) {
    extent = std::max(extent, s.offset_m.norm() + s.radius_m);
    r_tpl = std::max(r_tpl, s.radius_m);
  }
  const double s_max = sc.sd > 0.0 ? sc.hi : sc.mean;
  double cell = 2.0 * r_tpl * s_max;
  for (double r : sim.spheres().radius_m) cell = std::max(cell, 2.0 * r);
  SphereGrid grid(cell);
  for (std::size_t i = 0; i < sim.spheres().size(); ++i)
    grid.add(sim.spheres().position_m[i], sim.spheres().radius_m[i]);

  PortableNormal normal(sc.mean, sc.sd);
  const PortableUniform u01(0.0, 1.0);
  const std::uint64_t max_attempts =
      spec.max_attempts > 0 ? spec.max_attempts
                            : (spec.count > 0 ? 1000 * spec.count : std::uint64_t{1000000});
  const InsertionRegion& R = spec.region;
  std::vector<std::pair<Vec3, double>> world;
  std::vector<int> prims;
  std::uint64_t attempts = 0;
  // The scale is drawn once per body and kept while positions are tried (up to
  // `tries_per_body`), so crowding does not bias the size distribution towards small bodies.
  const std::uint64_t tries_per_body = 1000;
  bool have_scale = false;
  double s = sc.mean;
  std::uint64_t tries = 0;
  while (attempts < max_attempts) {
    if (spec.count > 0 && res.placed >= spec.count) break;
    if (spec.total_mass_kg > 0.0 && res.mass_kg >= spec.total_mass_kg) break;
    ++attempts;
    if (!have_scale || tries >= tries_per_body) {
      s = sc.mean;
      if (sc.sd > 0.0) {
        do s = normal(rng); while (s < sc.lo || s > sc.hi);
      }
      have_scale = true;
      tries = 0;
    }
    ++tries;
    BodyDef b = scaled_body(spec.body, s);
    const double e = extent * s;  // keep the whole body inside the region
    if (R.kind == InsertionRegion::Kind::box) {
      const Vec3 lo = R.lo_m + Vec3::Constant(e), hi = R.hi_m - Vec3::Constant(e);
      if ((hi - lo).minCoeff() < 0.0) { res.stop_reason = "the region is smaller than one particle"; return res; }
      // Drawn in a fixed order (the order of a call's arguments is unspecified in C++).
      const double fx = u01(rng), fy = u01(rng), fz = u01(rng);
      b.position_m = lo + Vec3(fx * (hi.x() - lo.x()), fy * (hi.y() - lo.y()), fz * (hi.z() - lo.z()));
    } else {
      const double rr = R.radius_m - e, hh = R.height_m - 2.0 * e;
      if (rr < 0.0 || hh < 0.0) { res.stop_reason = "the region is smaller than one particle"; return res; }
      const double rho = rr * std::sqrt(u01(rng)), phi = 2.0 * std::numbers::pi * u01(rng);
      b.position_m = R.base_m + Vec3(rho * std::cos(phi), rho * std::sin(phi), e + hh * u01(rng));
    }
    if (spec.random_orientation) b.orientation = uniform_random_rotation(rng);
    world.clear();
    bool ok = true;
    for (const SphereDef& sd : b.spheres) {
      const Vec3 p = b.position_m + b.orientation * sd.offset_m;
      if (grid.overlaps(p, sd.radius_m)) { ok = false; break; }
      for (const Wall& w : sim.walls()) {
        // Any primitive within a radius is an overlap (WallShape::near: before the shared-edge
        // rule, so a contact the rule gives to a neighbour still counts); a mesh answers from
        // its grid (candidates), not by testing every triangle.
        const Vec3 c = to_wall_frame(w.pose, p);
        w.shape->candidates(c, sd.radius_m, prims);
        for (int k : prims)
          if (w.shape->near(k, c, sd.radius_m)) { ok = false; break; }
        if (!ok) break;
      }
      if (!ok) break;
      world.push_back({p, sd.radius_m});
    }
    if (!ok) continue;
    for (const auto& [p, r] : world) grid.add(p, r);
    b.velocity_m_s = spec.velocity_m_s;
    sim.add_body(b);
    ++res.placed;
    res.mass_kg += b.mass_kg;
    have_scale = false;
  }
  res.complete = (spec.count == 0 || res.placed >= spec.count) &&
                 (spec.total_mass_kg <= 0.0 || res.mass_kg >= spec.total_mass_kg);
  std::ostringstream m;
  m << "placed " << res.placed << " bodies (" << res.mass_kg << " kg) in " << attempts << " attempts";
  if (!res.complete) m << "; the region is too full for more (enlarge it or insert in batches)";
  res.stop_reason = m.str();
  return res;
}

}  // namespace seedcal
