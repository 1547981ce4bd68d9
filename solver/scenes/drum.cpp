#include "solver/scenes/drum.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>

#include "solver/sim/settle.hpp"
#include "solver/walls/cylinder_shape.hpp"
#include "solver/walls/mesh_shape.hpp"
#include "solver/walls/motion_laws.hpp"

namespace seedcal {

void summarize_frame_angles(DrumResult& res) {
  std::vector<double> a;
  for (const DrumFrame& f : res.frames)
    if (f.fit.ok) a.push_back(f.angle_deg);
  res.measured_frames = static_cast<int>(a.size());
  res.failed_frames = static_cast<int>(res.frames.size() - a.size());
  // Mean and sample sd (two passes) over the measured frames only: a failed fit is no angle of 0.
  if (a.empty()) {
    res.dynamic_angle_of_repose_deg = std::numeric_limits<double>::quiet_NaN();
    res.angle_sd_deg = 0.0;
    return;
  }
  const double n = static_cast<double>(a.size());
  double mean = 0.0, ss = 0.0;
  for (double x : a) mean += x / n;
  for (double x : a) ss += (x - mean) * (x - mean);
  res.dynamic_angle_of_repose_deg = mean;
  res.angle_sd_deg = a.size() > 1 ? std::sqrt(ss / (n - 1.0)) : 0.0;
}

double drum_fill_height(double radius_m, double filling_rate) {
  // f(eps) = (eps - sin eps cos eps) / pi rises monotonically from 0 (eps = 0) to 1 (eps = pi):
  // bisection to machine precision.
  double lo = 0.0, hi = std::numbers::pi;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    const double f = (mid - std::sin(mid) * std::cos(mid)) / std::numbers::pi;
    (f < filling_rate ? lo : hi) = mid;
  }
  return radius_m * (1.0 - std::cos(0.5 * (lo + hi)));
}

double wall_layer_speed_ratio(const BodyState& bodies, double radius_m, double layer_m,
                              double omega_rad_s) {
  // The drum turns about +y through the origin: the shell's velocity at (x, z) is w (z, 0, -x),
  // so a body's speed along the turn is (z v_x - x v_z) / rho with rho = sqrt(x^2 + z^2).
  double moved = 0.0, wall = 0.0;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const Vec3& p = bodies.position_m[b];
    const double rho = std::hypot(p.x(), p.z());
    if (rho < radius_m - layer_m || rho == 0.0) continue;
    const Vec3& v = bodies.velocity_m_s[b];
    const double m = bodies.mass_kg[b];
    moved += m * (p.z() * v.x() - p.x() * v.z()) / rho;
    wall += m * omega_rad_s * rho;
  }
  return wall > 0.0 ? moved / wall : 0.0;
}

namespace {

// The protocol's phases, named once for its plan and its run (metrics.json `phases` beside
// `plan.phases`).
constexpr const char* kPhasePour = "pour";
constexpr const char* kPhaseSettle = "settle";
constexpr const char* kPhaseTurn = "turn";

// The fill is poured in up to 10 batches 0.15 s apart and settles for at most 1 s before the turn.
constexpr int kPourBatches = 10;
constexpr double kPourBatchInterval_s = 0.15;
constexpr double kFillSettleMaxTime_s = 1.0;

}  // namespace

RunPlan plan_drum(const DrumSpec& spec) {
  const double R = 0.5 * spec.diameter_m, D = spec.depth_m;
  const double g = spec.physics.gravity_m_s2.norm();
  const double w = spec.speed_rpm * 2.0 * std::numbers::pi / 60.0;
  const double mass = spec.filling_rate * std::numbers::pi * R * R * D * spec.bulk_density_kg_m3;
  const double rho = spec.physics.materials[spec.seeds.body.material].density_kg_m3;
  RunPlan p;
  p.dt_s = seed_time_step(spec.physics, spec.time_step, spec.seeds, std::sqrt(2.0 * g * R) + w * R);
  p.body = spec.seeds.body;
  p.physics = spec.physics;
  p.seeds = seeds_in_mass(spec.seeds, mass);
  p.spheres = p.seeds * static_cast<double>(spec.seeds.body.spheres.size());
  const double region_m3 = 1.5 * R * D * 1.35 * R;
  p.phases.push_back({kPhasePour, pour_time_s(mass, rho, region_m3, kPourBatches, kPourBatchInterval_s),
                      0.5 * p.spheres, true});
  p.phases.push_back({kPhaseSettle, settle_time_s(1.35 * R, g, kFillSettleMaxTime_s), p.spheres, true});
  double last = 0.0;
  for (double t : spec.frame_times_s) last = std::max(last, t);
  p.phases.push_back({kPhaseTurn, last, p.spheres, false});
  return p;
}

DrumResult run_drum(const DrumSpec& spec) {
  const auto wall_t0 = std::chrono::steady_clock::now();
  const double cpu0 = run_cpu_seconds(spec.threads);
  DrumResult res;
  const double R = 0.5 * spec.diameter_m, D = spec.depth_m;
  const double g = spec.physics.gravity_m_s2.norm();
  const double w = spec.speed_rpm * 2.0 * std::numbers::pi / 60.0;
  res.froude_number = w * w * R / g;
  res.fill_height_m = drum_fill_height(R, spec.filling_rate);
  const double dt = seed_time_step(spec.physics, spec.time_step, spec.seeds, std::sqrt(2.0 * g * R) + w * R);
  const double mass = spec.filling_rate * std::numbers::pi * R * R * D * spec.bulk_density_kg_m3;
  check_pour_memory(spec.physics, spec.seeds, mass, spec.threads, "diameter_m",
                    describe_rig({{"diameter_m", spec.diameter_m},
                                  {"depth_m", spec.depth_m},
                                  {"filling_rate", spec.filling_rate}}));
  Simulation sim(InteractionTable(spec.physics.materials, spec.physics.interactions),
                 seed_options(spec.physics, dt, spec.threads, spec.seed, spec.observer));
  // The drum: a closed cylinder whose axis (its frame's z) is the world y axis, centred on the
  // origin; it turns about +y.
  Wall drum;
  drum.name = "drum";
  drum.material = spec.drum_material;
  drum.pose.orientation = Quat(Eigen::AngleAxisd(-0.5 * std::numbers::pi, Vec3::UnitX()));  // z -> y
  drum.pose.origin_m = Vec3(0.0, -0.5 * D, 0.0);
  std::vector<std::size_t> turning;
  if (spec.shell_facets >= 3) {
    // A faceted shell: N rectangles (two triangles each) between the vertices R (cos t_k, sin t_k)
    // at z = 0 and z = D, in the drum's frame; the end faces stay discs, of a cylinder 5 % wider
    // whose lateral surface no seed inside the facets reaches.
    const int n = spec.shell_facets;
    std::vector<Triangle> tris;
    for (int k = 0; k < n; ++k) {
      const double a0 = 2.0 * std::numbers::pi * k / n, a1 = 2.0 * std::numbers::pi * (k + 1) / n;
      const Vec3 p0(R * std::cos(a0), R * std::sin(a0), 0.0), p1(R * std::cos(a1), R * std::sin(a1), 0.0);
      const Vec3 q0 = p0 + Vec3(0.0, 0.0, D), q1 = p1 + Vec3(0.0, 0.0, D);
      tris.push_back({p0, p1, q1});
      tris.push_back({p0, q1, q0});
    }
    Wall shell = drum;
    shell.name = "drum shell";
    shell.shape = std::make_shared<TriangleMeshShape>(tris, std::to_string(n) + " facets");
    drum.name = "drum ends";
    drum.shape = std::make_shared<CylinderShape>(1.05 * R, D, true, true, true);
    turning.push_back(sim.add_wall(shell));
  } else {
    drum.shape = std::make_shared<CylinderShape>(R, D, true, true, true);
  }
  turning.push_back(sim.add_wall(drum));

  FactorySpec fs;
  fs.body = spec.seeds.body;
  fs.scale = spec.seeds.scale;
  fs.region.lo_m = Vec3(-0.75 * R, -0.5 * D, -0.75 * R);
  fs.region.hi_m = Vec3(0.75 * R, 0.5 * D, 0.6 * R);
  begin_phase(res.run, sim, kPhasePour);
  pour_seeds(sim, fs, mass, kPourBatches, kPourBatchInterval_s);
  SettleCriteria sc;
  sc.max_time_s = kFillSettleMaxTime_s;
  sc.check_interval_s = 0.005;
  begin_phase(res.run, sim, kPhaseSettle);
  if (sim.failure().status == RunStatus::ok) run_until_settled(sim, sc);
  res.seeds = sim.bodies().size();

  begin_phase(res.run, sim, kPhaseTurn);
  const double t0 = sim.time_s();
  // Rotation laws take the absolute time; shift so the turn starts now.
  struct Delayed final : WallMotion {
    std::shared_ptr<WallMotion> inner;
    double start;
    void advance(Wall& wl, double t, double h) override { inner->advance(wl, t - start, h); }
    double max_speed_m_s(double e) const override { return inner->max_speed_m_s(e); }
  };
  for (std::size_t wi : turning) {
    auto delayed = std::make_shared<Delayed>();
    delayed->inner = std::make_shared<Rotation>(Vec3::UnitY(), Vec3::Zero(), w, sim.walls()[wi].pose);
    delayed->start = t0;
    sim.walls()[wi].motion = delayed;
  }

  double d = 0.0;
  for (const SphereDef& s : spec.seeds.body.spheres) d = std::max(d, 2.0 * (s.offset_m.norm() + s.radius_m));
  double ratio_sum = 0.0;
  res.run.stop_reason = "all frames taken";
  for (double tf : spec.frame_times_s) {
    if (!run_for(sim, std::max(0.0, t0 + tf - sim.time_s()))) {
      res.run.stop_reason = std::string("guard: ") + to_string(sim.failure().status);
      break;
    }
    std::vector<std::pair<double, double>> pts;
    double xmin = 1e9, xmax = -1e9;
    for (std::size_t i = 0; i < sim.spheres().size(); ++i) {
      const Vec3& p = sim.spheres().position_m[i];
      pts.push_back({p.x(), p.z() + sim.spheres().radius_m[i]});
      xmin = std::min(xmin, p.x());
      xmax = std::max(xmax, p.x());
    }
    const auto prof = upper_profile(pts, 0.5 * d);
    const double mid = 0.5 * (xmin + xmax), half = 0.5 * spec.fit_width_fraction * (xmax - xmin);
    std::vector<double> xs, zs;
    for (const auto& [x, z] : prof)
      if (std::abs(x - mid) <= half) {
        xs.push_back(x);
        zs.push_back(z);
      }
    DrumFrame fr{tf, 0.0, prof, fit_line(xs, zs)};
    fr.wall_layer_speed_ratio = wall_layer_speed_ratio(sim.bodies(), R, d, w);
    ratio_sum += fr.wall_layer_speed_ratio;
    res.slipping_frames += std::abs(fr.wall_layer_speed_ratio) < kSlippingSpeedRatio;
    if (fr.fit.ok) fr.angle_deg = std::atan(std::abs(fr.fit.slope)) * 180.0 / std::numbers::pi;
    res.frames.push_back(fr);
  }
  if (!res.frames.empty()) res.wall_layer_speed_ratio = ratio_sum / static_cast<double>(res.frames.size());
  summarize_frame_angles(res);
  res.run.failure = sim.failure();
  res.spheres = body_spheres(sim);
  finish_report(res.run, sim, cpu0, wall_t0);
  return res;
}

}  // namespace seedcal
