#include "solver/scenes/bench_beds.hpp"

#include <chrono>
#include <cmath>
#include <random>
#include <unordered_map>

#include "solver/scenes/free_drop.hpp"
#include "solver/sim/simulation.hpp"

namespace seedcal {
namespace {

Wall plane(const Vec3& point, const Vec3& normal) {
  Wall w;
  w.name = "plane";
  w.shape = std::make_shared<PlaneShape>(normal);
  w.material = 0;
  w.pose.origin_m = point;
  return w;
}

// Random sequential insertion of a body template in an axis-aligned region, as LIGGGHTS's
// insert/pack does: random position (and orientation), rejected if any sphere would overlap an
// already inserted one or leave the region (all_in). Overlaps are checked on a hash grid.
std::size_t insert_random(Simulation& sim, const BodyDef& tpl, std::size_t count, const Vec3& lo,
                          const Vec3& hi, bool rotate, std::uint64_t max_attempts) {
  double r_max = 0.0, extent = 0.0;
  for (const SphereDef& s : tpl.spheres) {
    r_max = std::max(r_max, s.radius_m);
    extent = std::max(extent, s.offset_m.norm() + s.radius_m);
  }
  const double cell = 2.0 * r_max;
  auto key = [&](const Vec3& p) {
    const auto ix = static_cast<std::int64_t>(std::floor(p.x() / cell));
    const auto iy = static_cast<std::int64_t>(std::floor(p.y() / cell));
    const auto iz = static_cast<std::int64_t>(std::floor(p.z() / cell));
    return (ix * 73856093) ^ (iy * 19349663) ^ (iz * 83492791);
  };
  std::unordered_multimap<std::int64_t, std::pair<Vec3, double>> grid;
  std::uniform_real_distribution<double> ux(lo.x() + extent, hi.x() - extent),
      uy(lo.y() + extent, hi.y() - extent), uz(lo.z() + extent, hi.z() - extent);
  auto& rng = sim.rng();
  std::size_t placed = 0;
  std::vector<std::pair<Vec3, double>> world;
  for (std::uint64_t a = 0; a < max_attempts && placed < count; ++a) {
    BodyDef b = tpl;
    b.position_m = Vec3(ux(rng), uy(rng), uz(rng));
    if (rotate) b.orientation = uniform_random_rotation(rng);
    world.clear();
    for (const SphereDef& s : b.spheres) world.push_back({b.position_m + b.orientation * s.offset_m, s.radius_m});
    bool ok = true;
    for (const auto& [p, r] : world) {
      for (int dx = -1; dx <= 1 && ok; ++dx)
        for (int dy = -1; dy <= 1 && ok; ++dy)
          for (int dz = -1; dz <= 1 && ok; ++dz) {
            const auto range = grid.equal_range(key(p + cell * Vec3(dx, dy, dz)));
            for (auto it = range.first; it != range.second; ++it)
              if ((it->second.first - p).norm() < it->second.second + r) { ok = false; break; }
          }
      if (!ok) break;
    }
    if (!ok) continue;
    for (const auto& w : world) grid.emplace(key(w.first), w);
    sim.add_body(b);
    ++placed;
  }
  return placed;
}

}  // namespace

BenchSpec settled_bed_spec() {
  BenchSpec s;
  s.name = "settled-bed";
  s.settle_steps = 80000;
  return s;
}

BenchSpec clump_bed_spec(std::vector<SphereXYZR> clump) {
  BenchSpec s;
  s.name = "clump-bed";
  s.clump = std::move(clump);
  s.settle_steps = 100000;
  return s;
}

BenchResult run_bench(const BenchSpec& spec) {
  const bool clumps = spec.name == "clump-bed";
  const Material seed{"seed", 1340.0, 1.65e8, 0.4};
  const InteractionTable table({seed}, {Interaction{"seed_seed", 0, 0, 0.45, 0.55, 0.05}});
  SimulationOptions opt;
  opt.contact.normal = NormalModel::hertz_mindlin;
  opt.contact.rolling = RollingModel::cdt;
  opt.dt_s = 5e-6;
  opt.skin_m = 0.0004;
  opt.profile = true;  // four clock reads per step: negligible against a 10,000-sphere step
  opt.threads = spec.threads;
  opt.seed = spec.seed;
  Simulation sim(table, opt);
  BodyDef tpl = clumps ? clump_body(spec.clump, seed.density_kg_m3, 0) : sphere_body(0.002, seed.density_kg_m3, 0);
  const Vec3 lo = clumps ? Vec3(0.006, 0.006, 0.006) : Vec3(0.0025, 0.0025, 0.0025);
  const Vec3 hi = clumps ? Vec3(0.094, 0.094, 0.294) : Vec3(0.0975, 0.0975, 0.1975);
  const std::size_t want = clumps ? 1000 : 10000;
  BenchResult res;
  const std::size_t placed = insert_random(sim, tpl, want, lo, hi, clumps, 300 * want);
  if (placed < want) res.failure = "inserted only " + std::to_string(placed) + " of " + std::to_string(want);
  sim.add_wall(plane(Vec3::Zero(), Vec3::UnitZ()));
  sim.add_wall(plane(Vec3::Zero(), Vec3::UnitX()));
  sim.add_wall(plane(Vec3(0.1, 0, 0), -Vec3::UnitX()));
  sim.add_wall(plane(Vec3::Zero(), Vec3::UnitY()));
  sim.add_wall(plane(Vec3(0, 0.1, 0), -Vec3::UnitY()));

  auto t0 = std::chrono::steady_clock::now();
  if (!sim.run(spec.settle_steps)) res.failure = sim.failure().message;
  res.settle_wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  sim.set_time_step(1e-6);
  const std::size_t builds0 = sim.neighbour_builds();
  const StepProfile p0 = sim.profile();
  t0 = std::chrono::steady_clock::now();
  if (res.failure.empty() && !sim.run(spec.timed_steps)) res.failure = sim.failure().message;
  res.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const StepProfile p1 = sim.profile();
  res.integrate_s = p1.integrate_s - p0.integrate_s;
  res.neighbour_s = p1.neighbour_s - p0.neighbour_s;
  res.contact_s = p1.contact_s - p0.contact_s;
  res.reduce_s = p1.reduce_s - p0.reduce_s;
  res.spheres = sim.spheres().size();
  res.bodies = sim.bodies().size();
  res.steps = spec.timed_steps;
  res.sphere_steps_per_second = static_cast<double>(res.spheres) * static_cast<double>(res.steps) / res.wall_seconds;
  res.contacts_per_sphere = (2.0 * static_cast<double>(sim.stats().sphere_contacts) +
                             static_cast<double>(sim.stats().wall_contacts)) / static_cast<double>(res.spheres);
  res.neighbour_builds = sim.neighbour_builds() - builds0;
  res.kinetic_energy_j = sim.kinetic_energy_j();
  return res;
}

}  // namespace seedcal
