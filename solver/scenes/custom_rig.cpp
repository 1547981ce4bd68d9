#include "solver/scenes/custom_rig.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "solver/sim/settle.hpp"
#include "solver/walls/motion_laws.hpp"

namespace seedcal {
namespace {

// The protocol's phases, named once for its plan and its run (metrics.json `phases` beside
// `plan.phases`).
constexpr const char* kPhaseFill = "fill";
constexpr const char* kPhaseSettle = "settle";
constexpr const char* kPhaseRun = "run";

// The settling criterion is checked this often (as the bulk-density scene checks it).
constexpr double kSettleCheck_s = 0.005;

// Height from the top of the fill region down to the lowest wall: the fall that sets the expected
// impact speed sqrt(2 g h) of the time step (seed_bed.hpp).
double drop_height_m(const CustomSpec& spec) {
  double lowest = spec.fill.region.lo_m.z();
  for (const CustomWall& w : spec.walls) lowest = std::min(lowest, w.lowest_z_m);
  return std::max(spec.fill.region.hi_m.z() - lowest, spec.fill.region.hi_m.z() - spec.fill.region.lo_m.z());
}

double region_volume_m3(const BoxRegion& r) { return (r.hi_m - r.lo_m).prod(); }

double seed_density(const CustomSpec& spec) {
  return spec.physics.materials[spec.seeds.body.material].density_kg_m3;
}

// The factory pours the fill in batches until its count or mass is placed; each batch is given
// `batch_interval_s` to fall out of the region and make room for the next.
void pour(Simulation& sim, const CustomSpec& spec, CustomResult& res) {
  FactorySpec fs;
  fs.body = spec.seeds.body;
  fs.scale = spec.seeds.scale;
  fs.region.kind = InsertionRegion::Kind::box;
  fs.region.lo_m = spec.fill.region.lo_m;
  fs.region.hi_m = spec.fill.region.hi_m;
  fs.velocity_m_s = spec.fill.velocity_m_s;
  fs.random_orientation = spec.fill.random_orientation;
  for (int batch = 0; batch < spec.fill.batches; ++batch) {
    FactorySpec b = fs;
    if (spec.fill.count > 0) {
      if (res.seeds_poured >= spec.fill.count) break;
      b.count = spec.fill.count - res.seeds_poured;
    } else {
      if (res.mass_poured_kg >= spec.fill.mass_kg) break;
      b.total_mass_kg = spec.fill.mass_kg - res.mass_poured_kg;
    }
    b.max_attempts = 100000;
    const FactoryResult r = insert_particles(sim, b);
    res.seeds_poured += r.placed;
    res.mass_poured_kg += r.mass_kg;
    if (r.placed == 0) break;
    if (!run_for(sim, spec.fill.batch_interval_s)) break;
  }
}

// Starts a wall's motion law now (the run phase began at t0_s).
void start_motion(Wall& wall, const CustomWall& w, double now_s, double t0_s) {
  if (w.motion == CustomWall::Motion::translate)
    wall.motion = std::make_shared<Schedule>(
        std::vector<Schedule::Segment>{{now_s, t0_s + w.stop_s, w.velocity_m_s}});
  else if (w.motion == CustomWall::Motion::rotate)
    wall.motion = std::make_shared<Rotation>(w.axis, w.axis_point_m, w.rate_rad_s, wall.pose, now_s);
}

// Records one sample of every measurement at `t_s` after the run began.
void sample(const Simulation& sim, const CustomSpec& spec, std::vector<PlaneCrossing>& planes,
            CustomResult& res, double t_s) {
  const BodyState& B = sim.bodies();
  std::vector<std::pair<Vec3, double>> spheres;
  std::size_t plane = 0;
  for (std::size_t m = 0; m < spec.measures.size(); ++m) {
    const CustomMeasure& cm = spec.measures[m];
    CustomSeries& s = res.series[m];
    s.time_s.push_back(t_s);
    switch (cm.kind) {
      case CustomMeasure::Kind::mass_in_region:
        s.value.push_back(mass_in_box(B.position_m, B.mass_kg, cm.region));
        break;
      case CustomMeasure::Kind::discharge_rate:
        planes[plane].update(B.id, B.position_m, B.mass_kg);
        s.value.push_back(planes[plane++].crossed_kg());
        break;
      case CustomMeasure::Kind::surface_height:
        if (spheres.empty())
          for (std::size_t i = 0; i < sim.spheres().size(); ++i)
            spheres.push_back({sim.spheres().position_m[i], sim.spheres().radius_m[i]});
        s.heights.push_back(surface_heights(spheres, surface_line_points(cm), cm.from_m.z(), cm.probe_radius_m));
        break;
    }
  }
}

}  // namespace

double custom_fill_mass_kg(const CustomSpec& spec) {
  if (spec.fill.count == 0) return spec.fill.mass_kg;
  return static_cast<double>(spec.fill.count) * seed_volume_m3(spec.seeds, seed_density(spec)) * seed_density(spec);
}

std::vector<Vec3> surface_line_points(const CustomMeasure& m) {
  std::vector<Vec3> p;
  const int n = std::max(m.points, 1);
  for (int k = 0; k < n; ++k)
    p.push_back(n == 1 ? m.from_m : m.from_m + (m.to_m - m.from_m) * (static_cast<double>(k) / (n - 1)));
  return p;
}

RunPlan plan_custom(const CustomSpec& spec) {
  const double g = spec.physics.gravity_m_s2.norm();
  const double rho = seed_density(spec);
  const double mass = custom_fill_mass_kg(spec);
  const double h = drop_height_m(spec);
  RunPlan p;
  p.dt_s = seed_time_step(spec.physics, spec.time_step, spec.seeds, std::sqrt(2.0 * g * h));
  p.body = spec.seeds.body;
  p.physics = spec.physics;
  p.seeds = spec.fill.count > 0 ? static_cast<double>(spec.fill.count) : seeds_in_mass(spec.seeds, mass);
  p.spheres = p.seeds * static_cast<double>(spec.seeds.body.spheres.size());
  p.phases.push_back({kPhaseFill,
                      pour_time_s(mass, rho, region_volume_m3(spec.fill.region), spec.fill.batches,
                                  spec.fill.batch_interval_s),
                      0.5 * p.spheres, true});
  p.phases.push_back({kPhaseSettle, settle_time_s(h, g, spec.settle_max_time_s), p.spheres, true});
  // Exact in time; the spheres are an upper bound when a sink takes the discharged seeds out.
  p.phases.push_back({kPhaseRun, spec.run_time_s, p.spheres, false});
  return p;
}

CustomResult run_custom(const CustomSpec& spec) {
  const auto wall_t0 = std::chrono::steady_clock::now();
  const double cpu0 = run_cpu_seconds(spec.threads);
  CustomResult res;
  const double g = spec.physics.gravity_m_s2.norm();
  const double dt = seed_time_step(spec.physics, spec.time_step, spec.seeds, std::sqrt(2.0 * g * drop_height_m(spec)));
  const Vec3 region = spec.fill.region.hi_m - spec.fill.region.lo_m;
  check_pour_memory(spec.physics, spec.seeds, custom_fill_mass_kg(spec), spec.threads, "fill",
                    describe_rig({{"fill region x", region.x()}, {"y", region.y()}, {"z", region.z()},
                                  {"mass_kg", custom_fill_mass_kg(spec)}}));
  Simulation sim(InteractionTable(spec.physics.materials, spec.physics.interactions),
                 seed_options(spec.physics, dt, spec.threads, spec.seed, spec.observer));
  for (const CustomWall& w : spec.walls) sim.add_wall(w.wall);

  begin_phase(res.run, sim, kPhaseFill);
  pour(sim, spec, res);
  begin_phase(res.run, sim, kPhaseSettle);
  SettleResult st;
  if (sim.failure().status == RunStatus::ok) {
    SettleCriteria sc;
    sc.energy_ratio = spec.settle_energy_ratio;
    sc.max_time_s = spec.settle_max_time_s;
    sc.check_interval_s = kSettleCheck_s;
    st = run_until_settled(sim, sc);
  }
  res.settle_reason = st.reason;

  // The run phase: motions start at their times, samples every sample_interval_s.
  begin_phase(res.run, sim, kPhaseRun);
  res.series.resize(spec.measures.size());
  std::vector<PlaneCrossing> planes;
  for (const CustomMeasure& m : spec.measures)
    if (m.kind == CustomMeasure::Kind::discharge_rate) planes.emplace_back(m.point_m, m.normal);
  const double t0 = sim.time_s();
  std::vector<bool> started(spec.walls.size(), false);
  const auto start_due = [&] {
    for (std::size_t w = 0; w < spec.walls.size(); ++w)
      if (!started[w] && spec.walls[w].motion != CustomWall::Motion::none &&
          sim.time_s() - t0 >= spec.walls[w].start_s - 0.5 * dt) {
        start_motion(sim.walls()[w], spec.walls[w], sim.time_s(), t0);
        started[w] = true;
      }
  };
  const auto samples = static_cast<int>(std::ceil(spec.run_time_s / spec.sample_interval_s - 1e-9));
  bool pictured = false;
  const auto record = [&](double t_s) {
    sample(sim, spec, planes, res, t_s);
    if (!pictured && t_s >= spec.picture_time_s - 0.5 * dt) {
      res.picture_time_s = t_s;
      res.spheres = body_spheres(sim);
      res.walls = sim.walls();
      pictured = true;
    }
    if (spec.sink_z_m) {
      const BodyState& B = sim.bodies();
      std::vector<char> below(B.size(), 0);
      for (std::size_t b = 0; b < B.size(); ++b) below[b] = B.position_m[b].z() < *spec.sink_z_m ? 1 : 0;
      const auto n = static_cast<std::size_t>(std::count(below.begin(), below.end(), 1));
      if (n > 0) {
        sim.remove_bodies([&below](std::uint32_t b) { return below[b] != 0; });
        res.seeds_removed += n;
      }
    }
  };
  if (sim.failure().status == RunStatus::ok) {
    start_due();
    record(0.0);
  }
  for (int k = 1; k <= samples && sim.failure().status == RunStatus::ok;) {
    const double next_sample = t0 + std::min(k * spec.sample_interval_s, spec.run_time_s);
    double next = next_sample;
    for (std::size_t w = 0; w < spec.walls.size(); ++w)
      if (!started[w] && spec.walls[w].motion != CustomWall::Motion::none)
        next = std::min(next, t0 + spec.walls[w].start_s);
    if (!run_for(sim, next - sim.time_s())) break;
    start_due();
    if (sim.time_s() >= next_sample - 0.5 * dt) {
      record(sim.time_s() - t0);
      ++k;
    }
  }
  for (std::size_t m = 0; m < spec.measures.size(); ++m)
    if (spec.measures[m].kind == CustomMeasure::Kind::discharge_rate)
      res.series[m].rate = steady_rate(res.series[m].time_s, res.series[m].value, spec.measures[m].fit_lo,
                                       spec.measures[m].fit_hi);
  if (!pictured) {
    res.picture_time_s = sim.time_s() - t0;
    res.spheres = body_spheres(sim);
    res.walls = sim.walls();
  }
  res.run.stop_reason = sim.failure().status != RunStatus::ok
                            ? std::string("guard: ") + to_string(sim.failure().status)
                            : "ran run_time_s = " + std::to_string(spec.run_time_s) + " s after " + st.reason;
  finish_report(res.run, sim, cpu0, wall_t0);
  return res;
}

}  // namespace seedcal
