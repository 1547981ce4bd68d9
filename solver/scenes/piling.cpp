#include "solver/scenes/piling.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>

#include "solver/sim/settle.hpp"
#include "solver/walls/cylinder_shape.hpp"
#include "solver/walls/motion_laws.hpp"

namespace seedcal {
namespace {

// The protocol's phases, named once for its plan and its run (metrics.json `phases` beside
// `plan.phases`).
constexpr const char* kPhasePour = "pour";
constexpr const char* kPhaseSettle = "settle";
constexpr const char* kPhaseLift = "lift";
constexpr const char* kPhaseHeap = "heap";

// The fill is poured in up to 20 batches 0.15 s apart and settles in the tube for at most 1.5 s.
constexpr int kPourBatches = 20;
constexpr double kPourBatchInterval_s = 0.15;
constexpr double kFillSettleMaxTime_s = 1.5;
// The tube rises at most this far above the fill's top.
constexpr double kLiftBeyondTop_m = 0.02;
// The heap is given at least this long to run out before it may count as settled.
constexpr double kHeapMinTime_s = 0.1;
// The slope the plan assumes for the heap (plan_piling).
constexpr double kPlanAngleOfRepose_rad = 30.0 * std::numbers::pi / 180.0;

}  // namespace

HeapMeasurement measure_heap(const std::vector<std::pair<Vec3, double>>& spheres,
                             const std::vector<Vec3>& body_centres, double seed_size_m, int azimuths,
                             double window_lo, double window_hi) {
  HeapMeasurement res;
  const double d = seed_size_m;
  // Heap radius: the radius holding 95 % of the seeds (a few seeds that rolled away do not count).
  std::vector<double> radial;
  for (const Vec3& c : body_centres) radial.push_back(std::hypot(c.x(), c.y()));
  std::sort(radial.begin(), radial.end());
  if (!radial.empty()) res.heap_radius_m = radial[static_cast<std::size_t>(0.95 * static_cast<double>(radial.size() - 1))];
  for (const auto& [p, r] : spheres) res.heap_height_m = std::max(res.heap_height_m, p.z() + r);
  double sum = 0.0, sum2 = 0.0, foot_sum = 0.0;
  int feet = 0;
  for (int a = 0; a < azimuths; ++a) {
    const double phi = 2.0 * std::numbers::pi * a / azimuths;
    const Vec3 dir(std::cos(phi), std::sin(phi), 0.0);
    std::vector<std::pair<double, double>> pts;
    for (const auto& [p, rad] : spheres) {
      const double along = p.x() * dir.x() + p.y() * dir.y();
      const double across = -p.x() * dir.y() + p.y() * dir.x();
      if (along > 0.0 && std::abs(across) < 0.5 * d) pts.push_back({along, p.z() + rad});
    }
    const auto prof = upper_profile(pts, 0.5 * d);
    // The sector's own heap height (its profile's top) and the foot: the first column outward of
    // the top that is down to one seed on the plate (z <= d). Fit where the side is between
    // window_lo and window_hi of the height, between the top and the foot.
    double h = 0.0, r_top = 0.0;
    for (const auto& [r, z] : prof)
      if (z > h) { h = z; r_top = r; }
    double r_foot = std::numeric_limits<double>::infinity();
    for (const auto& [r, z] : prof)
      if (r > r_top && z <= d) { r_foot = r; break; }
    if (std::isfinite(r_foot)) {
      foot_sum += r_foot;
      ++feet;
    }
    std::vector<double> xs, zs;
    for (const auto& [r, z] : prof)
      if (r >= r_top && r < r_foot && z >= window_lo * h && z <= window_hi * h) {
        xs.push_back(r);
        zs.push_back(z);
      }
    const LineFit f = fit_line(xs, zs);
    res.profiles.push_back(prof);
    res.fits.push_back(f);
    res.fit_ranges.push_back(xs.empty() ? std::pair<double, double>{0.0, 0.0}
                                        : std::pair<double, double>{xs.front(), xs.back()});
    if (f.ok) {
      const double ang = std::atan(-f.slope) * 180.0 / std::numbers::pi;
      res.sector_angles_deg.push_back(ang);
      sum += ang;
      sum2 += ang * ang;
    }
  }
  if (feet > 0) res.foot_radius_m = foot_sum / feet;
  const double n = static_cast<double>(res.sector_angles_deg.size());
  if (n > 0) {
    res.angle_deg = sum / n;
    res.angle_sd_deg = n > 1 ? std::sqrt(std::max(0.0, (sum2 - n * res.angle_deg * res.angle_deg) / (n - 1))) : 0.0;
  }
  return res;
}

RunPlan plan_piling(const PilingSpec& spec) {
  const double R = 0.5 * spec.tube_diameter_m;
  const double tube_h = 2.0 * spec.fill_height_m;
  const double g = spec.physics.gravity_m_s2.norm();
  const double rho = spec.physics.materials[spec.seeds.body.material].density_kg_m3;
  const double pour_kg = std::numbers::pi * R * R * spec.fill_height_m * rho * 0.55;
  RunPlan p;
  p.dt_s = seed_time_step(spec.physics, spec.time_step, spec.seeds, std::sqrt(2.0 * g * tube_h));
  p.body = spec.seeds.body;
  p.physics = spec.physics;
  p.seeds = seeds_in_mass(spec.seeds, pour_kg);
  p.spheres = p.seeds * static_cast<double>(spec.seeds.body.spheres.size());
  const double region_m3 = std::numbers::pi * R * R * (tube_h - 0.3 * spec.fill_height_m);
  p.phases.push_back({kPhasePour, pour_time_s(pour_kg, rho, region_m3, kPourBatches, kPourBatchInterval_s),
                      0.5 * p.spheres, true});
  p.phases.push_back({kPhaseSettle, settle_time_s(tube_h, g, kFillSettleMaxTime_s), p.spheres, true});
  // The lift stops once the rim clears the heap's top by a seed size. The fill (volume V) runs out
  // into a cone of slope theta, whose height is (3 V tan^2 theta / pi)^(1/3); theta is taken as
  // 30 deg, about the static angle of repose of grain seeds (31.2 to 31.8 deg for the paper's three
  // maize varieties, section 3.1). Never beyond the fill's top and 20 mm, where the run stops lifting.
  double seed_size = 0.0;
  for (const SphereDef& s : spec.seeds.body.spheres) seed_size = std::max(seed_size, 2.0 * (s.offset_m.norm() + s.radius_m));
  const double fill_m3 = std::numbers::pi * R * R * spec.fill_height_m;
  const double tan2 = std::pow(std::tan(kPlanAngleOfRepose_rad), 2);
  const double cone_m = std::cbrt(3.0 * fill_m3 * tan2 / std::numbers::pi);
  const double lift_m = std::min(cone_m + seed_size * spec.seeds.scale.mean, spec.fill_height_m + kLiftBeyondTop_m);
  p.phases.push_back({kPhaseLift, lift_m / spec.lift_speed_m_s, p.spheres, true});
  // The heap runs out and comes to rest: the fall of the fill's top and the bed's collisions.
  p.phases.push_back({kPhaseHeap, std::max(kHeapMinTime_s, settle_time_s(spec.fill_height_m, g, spec.max_time_s)),
                      p.spheres, true});
  return p;
}

PilingResult run_piling(const PilingSpec& spec) {
  const auto wall_t0 = std::chrono::steady_clock::now();
  const double cpu0 = run_cpu_seconds(spec.threads);
  PilingResult res;
  const double R = 0.5 * spec.tube_diameter_m;
  const double tube_h = 2.0 * spec.fill_height_m;
  const double g = spec.physics.gravity_m_s2.norm();
  const double dt = seed_time_step(spec.physics, spec.time_step, spec.seeds, std::sqrt(2.0 * g * tube_h));
  const double rho = spec.physics.materials[spec.seeds.body.material].density_kg_m3;
  const double pour_kg = std::numbers::pi * R * R * spec.fill_height_m * rho * 0.55;
  check_pour_memory(spec.physics, spec.seeds, pour_kg, spec.threads, "tube_diameter_m",
                    describe_rig({{"tube_diameter_m", spec.tube_diameter_m},
                                  {"fill_height_m", spec.fill_height_m}}));
  Simulation sim(InteractionTable(spec.physics.materials, spec.physics.interactions),
                 seed_options(spec.physics, dt, spec.threads, spec.seed, spec.observer));
  Wall plate;
  plate.name = "plate";
  plate.shape = std::make_shared<PlaneShape>(Vec3::UnitZ());
  plate.material = spec.plate_material;
  sim.add_wall(plate);
  Wall tube;
  tube.name = "tube";
  tube.shape = std::make_shared<CylinderShape>(R, tube_h, true, false, false);
  tube.material = spec.tube_material;
  const std::size_t tube_index = sim.add_wall(tube);

  FactorySpec fs;
  fs.body = spec.seeds.body;
  fs.scale = spec.seeds.scale;
  fs.region.kind = InsertionRegion::Kind::cylinder;
  fs.region.radius_m = R;
  fs.region.base_m = Vec3(0.0, 0.0, 0.3 * spec.fill_height_m);
  fs.region.height_m = tube_h - 0.3 * spec.fill_height_m;
  begin_phase(res.run, sim, kPhasePour);
  pour_seeds(sim, fs, pour_kg, kPourBatches, kPourBatchInterval_s);
  SettleCriteria sc;
  sc.max_time_s = kFillSettleMaxTime_s;
  sc.check_interval_s = 0.005;
  begin_phase(res.run, sim, kPhaseSettle);
  if (sim.failure().status == RunStatus::ok) run_until_settled(sim, sc);
  res.seeds = sim.bodies().size();
  const double top = highest_point_m(sim);
  // Lift the tube at the set speed until its lower rim clears the highest seed by a seed size
  // (checked every 10 ms): from then on nothing can touch it, so the tube stops there. The fill
  // drains as the tube rises, so the rim clears the seeds well below the fill's initial top
  // (at most top + 20 mm of lift).
  double seed_size = 0.0;
  for (const SphereDef& s : spec.seeds.body.spheres)
    seed_size = std::max(seed_size, 2.0 * (s.offset_m.norm() + s.radius_m));
  seed_size *= spec.seeds.scale.mean;
  const double lift = top + kLiftBeyondTop_m;
  begin_phase(res.run, sim, kPhaseLift);
  const double t0 = sim.time_s();
  sim.walls()[tube_index].motion = std::make_shared<Schedule>(
      std::vector<Schedule::Segment>{{t0, t0 + lift / spec.lift_speed_m_s, Vec3(0, 0, spec.lift_speed_m_s)}});
  while (sim.failure().status == RunStatus::ok && sim.time_s() < t0 + lift / spec.lift_speed_m_s) {
    run_for(sim, 0.01);
    if (sim.walls()[tube_index].pose.origin_m.z() > highest_point_m(sim) + seed_size) break;
  }
  res.lift_m = sim.walls()[tube_index].pose.origin_m.z();
  sim.walls()[tube_index].motion = nullptr;
  sim.walls()[tube_index].pose.velocity_m_s.setZero();
  SettleResult heap;
  begin_phase(res.run, sim, kPhaseHeap);
  if (sim.failure().status == RunStatus::ok) {
    sc.max_time_s = spec.max_time_s;
    sc.min_time_s = kHeapMinTime_s;
    heap = run_until_settled(sim, sc);
  }
  res.run.stop_reason = sim.failure().status != RunStatus::ok
                            ? std::string("guard: ") + to_string(sim.failure().status)
                            : heap.reason;

  // Profile per sector and line fits.
  double d = 0.0;
  for (const SphereDef& s : spec.seeds.body.spheres) d = std::max(d, 2.0 * (s.offset_m.norm() + s.radius_m));
  d *= spec.seeds.scale.mean;
  std::vector<std::pair<Vec3, double>> spheres;
  for (std::size_t i = 0; i < sim.spheres().size(); ++i)
    spheres.push_back({sim.spheres().position_m[i], sim.spheres().radius_m[i]});
  HeapMeasurement m = measure_heap(spheres, sim.bodies().position_m, d, spec.azimuths, spec.window_lo,
                                   spec.window_hi);
  res.angle_of_repose_deg = m.angle_deg;
  res.angle_sd_deg = m.angle_sd_deg;
  res.sector_angles_deg = std::move(m.sector_angles_deg);
  res.heap_radius_m = m.heap_radius_m;
  res.heap_height_m = m.heap_height_m;
  res.foot_radius_m = m.foot_radius_m;
  res.profiles = std::move(m.profiles);
  res.fits = std::move(m.fits);
  res.fit_ranges = std::move(m.fit_ranges);
  res.spheres = body_spheres(sim);
  finish_report(res.run, sim, cpu0, wall_t0);
  return res;
}

}  // namespace seedcal
