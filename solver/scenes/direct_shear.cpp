#include "solver/scenes/direct_shear.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>

#include "solver/scenes/settle.hpp"
#include "solver/walls/cylinder_shape.hpp"
#include "solver/walls/motion_laws.hpp"

namespace seedcal {

DirectShearResult run_direct_shear(const DirectShearSpec& spec) {
  const auto wall_t0 = std::chrono::steady_clock::now();
  const double cpu0 = run_cpu_seconds(spec.threads);
  DirectShearResult res;
  const double R = 0.5 * spec.diameter_m, H = spec.sample_height_m, half = 0.5 * H;
  const double guide = spec.pour_height_factor * H;
  const double area = std::numbers::pi * R * R;
  const double g = spec.physics.gravity_m_s2.norm();
  const double dt = seed_time_step(spec.physics, spec.time_step, spec.seeds, std::sqrt(2.0 * g * (H + guide)));
  const double rho = spec.physics.materials[spec.seeds.body.material].density_kg_m3;
  check_pour_memory(spec.physics, spec.seeds, area * H * rho * 0.62, spec.threads, "diameter_m",
                    describe_rig({{"diameter_m", spec.diameter_m},
                                  {"sample_height_m", spec.sample_height_m}}));
  Simulation sim(InteractionTable(spec.physics.materials, spec.physics.interactions),
                 seed_options(spec.physics, dt, spec.threads, spec.seed, spec.observer));

  // Lower ring with its floor (fixed); upper ring from mid-height up through the pour guide.
  Wall lower;
  lower.name = "lower_ring";
  lower.shape = std::make_shared<CylinderShape>(R, half, true, true, false);
  lower.material = spec.box_material;
  sim.add_wall(lower);
  Wall upper;
  upper.name = "upper_ring";
  upper.shape = std::make_shared<CylinderShape>(R, half + guide, true, false, false);
  upper.material = spec.box_material;
  upper.pose.origin_m = Vec3(0.0, 0.0, half);
  sim.add_wall(upper);

  // Pour: enough seeds to fill the sample at a solid fraction of 0.62 (more than any loose random
  // packing reaches), in batches from the guide.
  FactorySpec fs;
  fs.body = spec.seeds.body;
  fs.scale = spec.seeds.scale;
  fs.region.kind = InsertionRegion::Kind::cylinder;
  fs.region.radius_m = R;
  fs.region.base_m = Vec3(0.0, 0.0, 0.5 * H);
  fs.region.height_m = H + guide - 0.5 * H;
  pour_seeds(sim, fs, area * H * rho * 0.62, 10, 0.1);
  SettleCriteria sc;
  sc.max_time_s = 1.0;
  sc.check_interval_s = 0.005;
  if (sim.failure().status == RunStatus::ok) run_until_settled(sim, sc);
  if (spec.sample_density_kg_m3 > 0.0) {
    // Weigh in the specimen: keep the lowest seeds up to the specimen mass (the last one kept when
    // that brings the mass closer to it), remove the rest.
    const double target = spec.sample_density_kg_m3 * area * H;
    std::vector<std::uint32_t> order(sim.bodies().size());
    for (std::uint32_t b = 0; b < order.size(); ++b) order[b] = b;
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
      return sim.bodies().position_m[a].z() < sim.bodies().position_m[b].z();
    });
    std::vector<char> keep(order.size(), 0);
    double mass = 0.0;
    for (std::uint32_t b : order) {
      const double m = sim.bodies().mass_kg[b];
      if (mass + m > target && (mass + m) - target > target - mass) break;
      keep[b] = 1;
      mass += m;
    }
    res.sample_mass_kg = mass;
    sim.remove_bodies([&](std::uint32_t b) { return keep[b] == 0; });
  } else {
    // Level the sample: remove seeds whose centre lies above the sample height.
    sim.remove_bodies([&](std::uint32_t b) { return sim.bodies().position_m[b].z() > H; });
    for (std::size_t b = 0; b < sim.bodies().size(); ++b) res.sample_mass_kg += sim.bodies().mass_kg[b];
  }
  res.seeds = sim.bodies().size();

  // Consolidate under a servo lid.
  double top = 0.0;
  for (std::size_t i = 0; i < sim.spheres().size(); ++i)
    top = std::max(top, sim.spheres().position_m[i].z() + sim.spheres().radius_m[i]);
  Wall lid;
  lid.name = "lid";
  lid.shape = std::make_shared<PlaneShape>(-Vec3::UnitZ());
  lid.material = spec.box_material;
  lid.pose.origin_m = Vec3(0.0, 0.0, top + 0.0005);
  auto servo = std::make_shared<Servo>(-Vec3::UnitZ(), spec.normal_stress_pa * area, spec.lid_max_speed_m_s);
  lid.motion = servo;
  const std::size_t lid_index = sim.add_wall(lid);
  const std::size_t upper_index = 1;
  // Consolidated when the lid holds the stress to 1 % and has stopped moving (< 1 um/ms).
  double t_end = sim.time_s() + spec.consolidation_max_time_s;
  double last_z = sim.walls()[lid_index].pose.origin_m.z();
  while (sim.failure().status == RunStatus::ok && sim.time_s() < t_end) {
    if (!run_for(sim, 0.002)) break;
    const Wall& l = sim.walls()[lid_index];
    const double z = l.pose.origin_m.z();
    const bool held = std::abs(servo->measured_force_n(l) / servo->target_force_n() - 1.0) < 0.01;
    if (held && std::abs(z - last_z) < 2e-6) break;
    last_z = z;
  }

  // Shear: the upper ring and the lid move along +x.
  const Vec3 v(spec.shear_speed_m_s, 0.0, 0.0);
  const double ring_z0 = sim.walls()[upper_index].pose.origin_m.z();
  if (spec.upper_ring_fixed) {
    sim.walls()[upper_index].motion = std::make_shared<ConstantVelocity>(v);
  } else {
    // Resting on the lower ring under its weight m g: a servo that holds the seeds' upward push at
    // m g lifts the ring when they push harder and sets it back on its seat when they push less.
    auto ring = std::make_shared<Servo>(-Vec3::UnitZ(), spec.upper_ring_mass_kg * g, spec.lid_max_speed_m_s);
    ring->set_seat(sim.walls()[upper_index].pose.origin_m);
    ring->set_transverse_velocity(v);
    sim.walls()[upper_index].motion = ring;
  }
  servo->set_transverse_velocity(v);
  const double z0 = sim.walls()[lid_index].pose.origin_m.z();
  res.consolidated_height_m = z0;
  {
    const BodyState& B = sim.bodies();
    const SphereState& S = sim.spheres();
    for (std::size_t b = 0; b < B.size(); ++b) {
      double zlo = std::numeric_limits<double>::infinity(), zhi = -zlo;
      for (std::uint32_t i = B.first_sphere[b]; i < B.first_sphere[b + 1]; ++i) {
        zlo = std::min(zlo, S.position_m[i].z() - S.radius_m[i]);
        zhi = std::max(zhi, S.position_m[i].z() + S.radius_m[i]);
      }
      if (zlo < half && zhi > half) ++res.seeds_across_split;
    }
  }
  const double x0 = sim.walls()[upper_index].pose.origin_m.x();
  const auto per_record = std::max<std::uint64_t>(1, static_cast<std::uint64_t>(spec.record_interval_s / dt));
  double sigma_sum = 0.0;
  std::size_t n = 0;
  res.run.stop_reason = "shear displacement reached";
  while (sim.walls()[upper_index].pose.origin_m.x() - x0 < spec.shear_displacement_m) {
    if (!sim.run(per_record)) {
      res.run.stop_reason = std::string("guard: ") + to_string(sim.failure().status);
      break;
    }
    const Wall& up = sim.walls()[upper_index];
    const Wall& l = sim.walls()[lid_index];
    // Force the seeds exert on the moving half along -x resists the motion: shear force = -F_x.
    const double tau = -(up.force_n.x() + l.force_n.x()) / area;
    const double sigma = servo->measured_force_n(l) / area;
    const double lift = up.pose.origin_m.z() - ring_z0;
    res.upper_ring_lift_m = std::max(res.upper_ring_lift_m, lift);
    res.curve.push_back({up.pose.origin_m.x() - x0, tau, sigma, l.pose.origin_m.z(), 0.0, lift});
    sigma_sum += sigma;
    ++n;
  }
  res.run.failure = sim.failure();
  // Peak of the curve smoothed by a centred moving average over `smoothing_m` of displacement:
  // the instantaneous wall force of a coarse sample carries contact-scale spikes that the lab's
  // load cell and its reading rate average out.
  // The ring moves one way, so the samples are sorted by displacement and each window is a range
  // [lo, hi) that only moves forward (linear in the samples, not quadratic); the window's samples
  // are summed in order.
  const auto within = [&](std::size_t m, std::size_t k) {
    return std::abs(res.curve[m].displacement_m - res.curve[k].displacement_m) <= 0.5 * spec.smoothing_m;
  };
  const bool sorted = std::is_sorted(res.curve.begin(), res.curve.end(), [](const ShearSample& a, const ShearSample& b) {
    return a.displacement_m < b.displacement_m;
  });
  std::size_t lo = 0, hi = 0;
  for (std::size_t k = 0; k < res.curve.size(); ++k) {
    if (sorted) {
      while (!within(lo, k)) ++lo;
      if (hi < k + 1) hi = k + 1;
      while (hi < res.curve.size() && within(hi, k)) ++hi;
    } else {
      lo = 0;
      hi = res.curve.size();
    }
    double sum = 0.0;
    int n_avg = 0;
    for (std::size_t m = lo; m < hi; ++m)
      if (within(m, k)) {
        sum += res.curve[m].shear_stress_pa;
        ++n_avg;
      }
    res.curve[k].smoothed_shear_stress_pa = sum / n_avg;
  }
  // Failure as in GB/T 50123: the peak, or the stress at the failure displacement (4 mm) when the
  // curve has no peak before it.
  for (const ShearSample& s : res.curve)
    if (s.displacement_m <= spec.failure_displacement_m &&
        s.smoothed_shear_stress_pa > res.shear_strength_pa) {
      res.shear_strength_pa = s.smoothed_shear_stress_pa;
      res.displacement_at_peak_m = s.displacement_m;
    }
  res.mean_normal_stress_pa = n > 0 ? sigma_sum / static_cast<double>(n) : 0.0;
  res.stress_ratio = res.mean_normal_stress_pa > 0 ? res.shear_strength_pa / res.mean_normal_stress_pa : 0.0;
  res.dilation_m = res.curve.empty() ? 0.0 : res.curve.back().lid_height_m - z0;
  // Inertial number with gamma_dot = v / d (shear band ~ one seed), d = the seed's bounding size.
  double d = 0.0;
  for (const SphereDef& s : spec.seeds.body.spheres) d = std::max(d, 2.0 * (s.offset_m.norm() + s.radius_m));
  res.inertial_number = spec.shear_speed_m_s / d * d * std::sqrt(rho / spec.normal_stress_pa);
  res.spheres = body_spheres(sim);
  finish_report(res.run, sim, cpu0, wall_t0);
  return res;
}

}  // namespace seedcal
