#include "solver/scenes/direct_shear.hpp"
#include "solver/scenes/shear_curve.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "solver/sim/settle.hpp"
#include "solver/walls/cylinder_shape.hpp"
#include "solver/walls/motion_laws.hpp"
#include "solver/walls/servo_wall.hpp"
#include "solver/walls/tube_shape.hpp"

namespace seedcal {

const char* to_string(ShearBoxGeometry g) { return g == ShearBoxGeometry::zj ? "zj" : "shells"; }

namespace {

// The protocol's phases, named once for its plan and its run (metrics.json `phases` beside
// `plan.phases`).
constexpr const char* kPhasePour = "pour";
constexpr const char* kPhaseSettle = "settle";
constexpr const char* kPhaseConsolidate = "consolidate";
constexpr const char* kPhaseShear = "shear";

// Seeds poured for the specimen: enough to fill it at a solid fraction of 0.62, more than any loose
// random packing of convex grains reaches, in ten batches 0.1 s apart.
constexpr double kPourSolidFraction = 0.62;
constexpr int kPourBatches = 10;
constexpr double kPourBatchInterval_s = 0.1;
// The poured seeds settle for at most this long before the specimen is formed.
constexpr double kSettleMaxTime_s = 1.0;
// The servo cap starts this far above the highest seed.
constexpr double kCapStartClearance_m = 0.0005;
// The cap's radial clearance in the upper ring's bore and its thickness (only its lower face
// touches seeds).
constexpr double kCapClearance_m = 0.0001;
constexpr double kCapThickness_m = 0.005;
// Consolidated when the cap holds the stress to 1 % and has moved less than 2 um over the last
// check interval of 2 ms (1 mm/s: far below the cap's approach speed, and a drift that would move it
// a fraction of a seed's elastic overlap over the shear).
constexpr double kConsolidationCheck_s = 0.002;
constexpr double kConsolidationStressTolerance = 0.01;
constexpr double kConsolidationDrift_m = 2e-6;

struct Rig {
  std::size_t upper = 0, cap = 0;  // wall indices
  std::shared_ptr<Servo> cap_servo;
};

// The rings (and the floor of the zj box). The upper ring continues up through the pour guide.
void add_rings(Simulation& sim, const DirectShearSpec& spec, Rig& rig) {
  const double R = 0.5 * spec.diameter_m, H = spec.sample_height_m, half = 0.5 * H;
  const double guide = spec.pour_height_factor * H;
  Wall lower, upper;
  lower.name = "lower_ring";
  upper.name = "upper_ring";
  lower.material = upper.material = spec.box_material;
  if (spec.geometry == ShearBoxGeometry::zj) {
    const double g = spec.ring_gap_m, outer = R + spec.ring_wall_thickness_m;
    Wall floor;
    floor.name = "floor";
    floor.material = spec.box_material;
    floor.shape = std::make_shared<PlaneShape>(Vec3::UnitZ());
    sim.add_wall(floor);
    lower.shape = std::make_shared<TubeShape>(R, outer, half - 0.5 * g);
    upper.shape = std::make_shared<TubeShape>(R, outer, half - 0.5 * g + guide);
    upper.pose.origin_m = Vec3(0.0, 0.0, half + 0.5 * g);
  } else {
    lower.shape = std::make_shared<CylinderShape>(R, half, true, true, false);
    upper.shape = std::make_shared<CylinderShape>(R, half + guide, true, false, false);
    upper.pose.origin_m = Vec3(0.0, 0.0, half);
  }
  sim.add_wall(lower);
  rig.upper = sim.add_wall(upper);
}

// Pours and settles the seeds, then forms the specimen: weighed in to `sample_density_kg_m3`
// (the lowest seeds up to its mass, the last one kept when that brings the mass closer), or
// levelled (seeds whose centre lies above the sample height removed). Returns its mass.
double form_specimen(Simulation& sim, const DirectShearSpec& spec, RunReport& report) {
  const double R = 0.5 * spec.diameter_m, H = spec.sample_height_m;
  const double area = std::numbers::pi * R * R;
  const double rho = spec.physics.materials[spec.seeds.body.material].density_kg_m3;
  FactorySpec fs;
  fs.body = spec.seeds.body;
  fs.scale = spec.seeds.scale;
  fs.region.kind = InsertionRegion::Kind::cylinder;
  fs.region.radius_m = R;
  fs.region.base_m = Vec3(0.0, 0.0, 0.5 * H);
  fs.region.height_m = 0.5 * H + spec.pour_height_factor * H;
  begin_phase(report, sim, kPhasePour);
  pour_seeds(sim, fs, area * H * rho * kPourSolidFraction, kPourBatches, kPourBatchInterval_s);
  SettleCriteria sc;
  sc.max_time_s = kSettleMaxTime_s;
  sc.check_interval_s = 0.005;
  begin_phase(report, sim, kPhaseSettle);
  if (sim.failure().status == RunStatus::ok) run_until_settled(sim, sc);
  double mass = 0.0;
  if (spec.sample_density_kg_m3 > 0.0) {
    const double target = spec.sample_density_kg_m3 * area * H;
    std::vector<std::uint32_t> order(sim.bodies().size());
    for (std::uint32_t b = 0; b < order.size(); ++b) order[b] = b;
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
      return sim.bodies().position_m[a].z() < sim.bodies().position_m[b].z();
    });
    std::vector<char> keep(order.size(), 0);
    for (std::uint32_t b : order) {
      const double m = sim.bodies().mass_kg[b];
      if (mass + m > target && (mass + m) - target > target - mass) break;
      keep[b] = 1;
      mass += m;
    }
    sim.remove_bodies([&](std::uint32_t b) { return keep[b] == 0; });
  } else {
    sim.remove_bodies([&](std::uint32_t b) { return sim.bodies().position_m[b].z() > H; });
    for (std::size_t b = 0; b < sim.bodies().size(); ++b) mass += sim.bodies().mass_kg[b];
  }
  return mass;
}

// The servo cap just above the highest seed: a disc of the bore's diameter inside the upper ring
// (zj) or an unbounded plane (shells).
void add_cap(Simulation& sim, const DirectShearSpec& spec, Rig& rig) {
  const double R = 0.5 * spec.diameter_m;
  const double top = highest_point_m(sim);
  Wall cap;
  cap.name = "lid";
  cap.material = spec.box_material;
  cap.pose.origin_m = Vec3(0.0, 0.0, top + kCapStartClearance_m);
  if (spec.geometry == ShearBoxGeometry::zj)
    cap.shape = std::make_shared<TubeShape>(0.0, R - kCapClearance_m, kCapThickness_m);
  else
    cap.shape = std::make_shared<PlaneShape>(-Vec3::UnitZ());
  rig.cap_servo = std::make_shared<Servo>(-Vec3::UnitZ(), spec.normal_stress_pa * std::numbers::pi * R * R,
                                          spec.lid_max_speed_m_s);
  cap.motion = rig.cap_servo;
  rig.cap = sim.add_wall(cap);
}

void consolidate(Simulation& sim, const DirectShearSpec& spec, const Rig& rig) {
  const double t_end = sim.time_s() + spec.consolidation_max_time_s;
  double last_z = sim.walls()[rig.cap].pose.origin_m.z();
  while (sim.failure().status == RunStatus::ok && sim.time_s() < t_end) {
    if (!run_for(sim, kConsolidationCheck_s)) break;
    const Wall& c = sim.walls()[rig.cap];
    const double z = c.pose.origin_m.z();
    const bool held = std::abs(rig.cap_servo->measured_force_n(c) / rig.cap_servo->target_force_n() - 1.0) <
                      kConsolidationStressTolerance;
    if (held && std::abs(z - last_z) < kConsolidationDrift_m) break;
    last_z = z;
  }
}

// Seeds whose clump reaches across the split plane z = H/2: what interlocks the two halves.
std::size_t seeds_across(const Simulation& sim, double split_z) {
  const BodyState& B = sim.bodies();
  const SphereState& S = sim.spheres();
  std::size_t n = 0;
  for (std::size_t b = 0; b < B.size(); ++b) {
    double zlo = std::numeric_limits<double>::infinity(), zhi = -zlo;
    for (std::uint32_t i = B.first_sphere[b]; i < B.first_sphere[b + 1]; ++i) {
      zlo = std::min(zlo, S.position_m[i].z() - S.radius_m[i]);
      zhi = std::max(zhi, S.position_m[i].z() + S.radius_m[i]);
    }
    if (zlo < split_z && zhi > split_z) ++n;
  }
  return n;
}

// The rig cut through its axis in the x-z plane at the end of shear (DirectShearResult).
std::vector<std::array<double, 4>> rig_outline(const Simulation& sim, const DirectShearSpec& spec) {
  std::vector<std::array<double, 4>> out;
  for (const Wall& w : sim.walls()) {
    const Vec3& o = w.pose.origin_m;
    if (const auto* t = dynamic_cast<const TubeShape*>(w.shape.get())) {
      const double a = t->inner_radius_m(), b = t->outer_radius_m(), top = o.z() + t->length_m();
      if (a > 0.0) {
        out.push_back({o.x() - b, o.z(), o.x() - a, top});
        out.push_back({o.x() + a, o.z(), o.x() + b, top});
      } else {
        out.push_back({o.x() - b, o.z(), o.x() + b, top});
      }
    } else if (const auto* c = dynamic_cast<const CylinderShape*>(w.shape.get())) {
      const double r = c->radius_m(), top = o.z() + c->length_m();
      out.push_back({o.x() - r, o.z(), o.x() - r, top});
      out.push_back({o.x() + r, o.z(), o.x() + r, top});
    } else {  // a plane: the floor, or the shells rig's lid, drawn across the box
      const double r = 0.5 * spec.diameter_m + spec.shear_displacement_m;
      out.push_back({o.x() - r, o.z(), o.x() + r, o.z()});
    }
  }
  return out;
}

}  // namespace

RunPlan plan_direct_shear(const DirectShearSpec& spec) {
  const double R = 0.5 * spec.diameter_m, H = spec.sample_height_m;
  const double area = std::numbers::pi * R * R;
  const double g = spec.physics.gravity_m_s2.norm();
  const double guide = spec.pour_height_factor * H;
  const double rho = spec.physics.materials[spec.seeds.body.material].density_kg_m3;
  const double pour_kg = area * H * rho * kPourSolidFraction;
  const auto per_seed = static_cast<double>(spec.seeds.body.spheres.size());
  RunPlan p;
  p.dt_s = seed_time_step(spec.physics, spec.time_step, spec.seeds, std::sqrt(2.0 * g * (H + guide)));
  p.body = spec.seeds.body;
  p.physics = spec.physics;
  p.seeds = seeds_in_mass(spec.seeds, pour_kg);
  p.spheres = p.seeds * per_seed;
  // The specimen: weighed in, or levelled at a loose random packing's solid fraction (about 0.55).
  const double specimen_kg = spec.sample_density_kg_m3 > 0.0 ? spec.sample_density_kg_m3 * area * H : 0.55 * rho * area * H;
  const double specimen = std::min(p.seeds, seeds_in_mass(spec.seeds, specimen_kg)) * per_seed;
  const double region_m3 = area * (0.5 * H + guide);
  p.phases.push_back({kPhasePour, pour_time_s(pour_kg, rho, region_m3, kPourBatches, kPourBatchInterval_s),
                      0.5 * p.spheres, true});
  p.phases.push_back({kPhaseSettle, settle_time_s(H + guide, g, kSettleMaxTime_s), p.spheres, true});
  // The cap closes its start clearance and the bed's response to the stress dies out.
  p.phases.push_back({kPhaseConsolidate, settle_time_s(0.0, g, spec.consolidation_max_time_s), specimen, true,
                      spec.normal_stress_pa});
  p.phases.push_back({kPhaseShear, spec.shear_displacement_m / spec.shear_speed_m_s, specimen, false, spec.normal_stress_pa});
  return p;
}

DirectShearResult run_direct_shear(const DirectShearSpec& spec) {
  const auto wall_t0 = std::chrono::steady_clock::now();
  const double cpu0 = run_cpu_seconds(spec.threads);
  DirectShearResult res;
  const double R = 0.5 * spec.diameter_m, H = spec.sample_height_m, half = 0.5 * H;
  const double area = std::numbers::pi * R * R;
  const double g = spec.physics.gravity_m_s2.norm();
  const double guide = spec.pour_height_factor * H;
  const double dt = seed_time_step(spec.physics, spec.time_step, spec.seeds, std::sqrt(2.0 * g * (H + guide)));
  const double rho = spec.physics.materials[spec.seeds.body.material].density_kg_m3;
  check_pour_memory(spec.physics, spec.seeds, area * H * rho * kPourSolidFraction, spec.threads, "diameter_m",
                    describe_rig({{"diameter_m", spec.diameter_m},
                                  {"sample_height_m", spec.sample_height_m}}));
  Simulation sim(InteractionTable(spec.physics.materials, spec.physics.interactions),
                 seed_options(spec.physics, dt, spec.threads, spec.seed, spec.observer));
  Rig rig;
  add_rings(sim, spec, rig);
  res.sample_mass_kg = form_specimen(sim, spec, res.run);
  res.seeds = sim.bodies().size();
  add_cap(sim, spec, rig);
  begin_phase(res.run, sim, kPhaseConsolidate);
  consolidate(sim, spec, rig);
  begin_phase(res.run, sim, kPhaseShear);

  // Shear: the upper ring and the cap move along +x.
  const Vec3 v(spec.shear_speed_m_s, 0.0, 0.0);
  const double ring_z0 = sim.walls()[rig.upper].pose.origin_m.z();
  if (spec.upper_ring_fixed) {
    sim.walls()[rig.upper].motion = std::make_shared<ConstantVelocity>(v);
  } else {
    // Resting on its seat under its weight m g: a servo that holds the seeds' upward push at m g
    // lifts the ring when they push harder and sets it back on its seat when they push less.
    auto ring = std::make_shared<Servo>(-Vec3::UnitZ(), spec.upper_ring_mass_kg * g, spec.lid_max_speed_m_s);
    ring->set_seat(sim.walls()[rig.upper].pose.origin_m);
    ring->set_transverse_velocity(v);
    sim.walls()[rig.upper].motion = ring;
  }
  rig.cap_servo->set_transverse_velocity(v);
  const double z0 = sim.walls()[rig.cap].pose.origin_m.z();
  res.consolidated_height_m = z0;
  res.seeds_across_split = seeds_across(sim, half);
  const double x0 = sim.walls()[rig.upper].pose.origin_m.x();
  const auto per_record = std::max<std::uint64_t>(1, static_cast<std::uint64_t>(spec.record_interval_s / dt));
  double sigma_sum = 0.0;
  std::size_t n = 0;
  res.run.stop_reason = "shear displacement reached";
  while (sim.failure().status == RunStatus::ok &&
         sim.walls()[rig.upper].pose.origin_m.x() - x0 < spec.shear_displacement_m) {
    if (!sim.run(per_record)) break;
    const Wall& up = sim.walls()[rig.upper];
    const Wall& c = sim.walls()[rig.cap];
    // The force the seeds exert on the moving half along -x resists the motion: shear force = -F_x.
    const double tau = -(up.force_n.x() + c.force_n.x()) / area;
    const double sigma = rig.cap_servo->measured_force_n(c) / area;
    const double lift = up.pose.origin_m.z() - ring_z0;
    res.upper_ring_lift_m = std::max(res.upper_ring_lift_m, lift);
    res.curve.push_back({up.pose.origin_m.x() - x0, tau, sigma, c.pose.origin_m.z(), 0.0, lift});
    sigma_sum += sigma;
    ++n;
  }
  if (sim.failure().status != RunStatus::ok)
    res.run.stop_reason = std::string("guard: ") + to_string(sim.failure().status);
  res.run.failure = sim.failure();

  // Failure as in GB/T 50123 (scenes/shear_curve.hpp).
  smooth_curve(res.curve, spec.smoothing_m);
  const ShearFailure failure = read_failure(res.curve, spec.failure_displacement_m);
  res.shear_strength_pa = failure.shear_strength_pa;
  res.displacement_at_peak_m = failure.displacement_m;
  res.curve_shape = curve_shape(res.curve, spec.smoothing_m);
  res.mean_normal_stress_pa = n > 0 ? sigma_sum / static_cast<double>(n) : 0.0;
  res.stress_ratio = res.mean_normal_stress_pa > 0 ? res.shear_strength_pa / res.mean_normal_stress_pa : 0.0;
  res.dilation_m = res.curve.empty() ? 0.0 : res.curve.back().lid_height_m - z0;
  // Inertial number I = gamma_dot d sqrt(rho / sigma) with gamma_dot = v / d: d cancels.
  res.inertial_number = spec.shear_speed_m_s * std::sqrt(rho / spec.normal_stress_pa);
  res.spheres = body_spheres(sim);
  res.rig_outline_m = rig_outline(sim, spec);
  finish_report(res.run, sim, cpu0, wall_t0);
  return res;
}

}  // namespace seedcal
