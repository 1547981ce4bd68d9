#include "solver/scenes/cost_probe.hpp"

#include <algorithm>
#include <cmath>

#include "solver/scenes/seed_bed.hpp"
#include "solver/sim/particle_factory.hpp"
#include "solver/walls/box_shape.hpp"
#include "solver/walls/servo_wall.hpp"

namespace seedcal {
namespace {

// About 1,500 spheres: enough that the per-step fixed costs do not count, few enough that the
// probe costs a small part of one run of a bulk scene. At least 12 bodies: a fine clump's seeds
// then cover a fifth of the box's floor and touch it and some neighbours; a bed two seeds deep
// costs the same a sphere-step (docs/results/cost_estimate.md).
constexpr double kProbeSpheres = 1500.0;
constexpr std::size_t kMinBodies = 12, kMaxBodies = 400;
// A loaded bed: at least 160 bodies, two to three seeds deep in the box below (six seed lengths
// square: about 60 seeds lying flat make a layer), so the lid's load reaches the bed through a layer
// of seeds as a shear box's cap does. The lid starts half a millimetre above the bed, moves at up
// to 0.5 m/s (the probe measures cost, not physics) and is taken as loaded once it holds the stress
// to 5 %, or after kMaxLoadSteps.
constexpr std::size_t kMinLoadedBodies = 160;
constexpr double kLidClearance_m = 0.0005, kLidSpeed_m_s = 0.5, kLoadTolerance = 0.05;
constexpr std::uint64_t kLoadCheckSteps = 100, kMaxLoadSteps = 40000;
// The bodies are placed in a region four bed heights tall (about a quarter of it solid, where the
// factory's random placement jams) and fall under five times gravity, which brings them into a bed
// in a fifth of the time: the probe measures cost, not physics. They fall for one and a half times
// the fall time from the region's top (the last half for the bed's collisions to die out), in at
// most kMaxFallSteps or kMaxFallSphereSteps sphere-steps, whichever allows more; where that is too
// few (a fine clump at its short step) gravity is raised further so the fall fits: a bed still in
// flight, whose spheres touch nothing, would price a fine clump far below its cost.
constexpr double kGravityFactor = 5.0;
constexpr double kRegionSolidFraction = 0.15;
constexpr std::uint64_t kTimedSteps = 1000;
constexpr double kFallAndSettle = 1.5;
constexpr double kMaxFallSteps = 20000.0, kMaxFallSphereSteps = 4e8;
constexpr double kMaxFlightSteps = 20000.0;

}  // namespace

CostProbe probe_sphere_step_cost(const PhysicsSpec& physics, const BodyDef& body, double dt_s, int threads,
                                 bool bed, double confining_stress_pa) {
  CostProbe res;
  if (!bed) {
    SimulationOptions opt;
    opt.contact = physics.contact;
    opt.gravity_m_s2 = Vec3::Zero();
    opt.dt_s = dt_s;
    opt.threads = 1;
    Simulation sim(InteractionTable(physics.materials, physics.interactions), opt);
    sim.add_body(body);
    // As many sphere-steps as the bed probe times, but at most kMaxFlightSteps: a body of one or two
    // spheres costs its per-step overheads, which that many steps measure well enough.
    const double per_body = static_cast<double>(std::max<std::size_t>(1, body.spheres.size()));
    const auto steps = static_cast<std::uint64_t>(
        std::clamp(kProbeSpheres * static_cast<double>(kTimedSteps) / per_body, 1000.0, kMaxFlightSteps));
    const double cpu0 = run_cpu_seconds(1);
    sim.run(steps);
    res.probe_cpu_s = run_cpu_seconds(1) - cpu0;
    res.bodies = 1;
    res.spheres = sim.spheres().size();
    res.timed_steps = steps;
    if (res.spheres > 0) res.cpu_s_per_sphere_step = res.probe_cpu_s / (static_cast<double>(res.spheres) * static_cast<double>(steps));
    return res;
  }
  const double per_body = static_cast<double>(std::max<std::size_t>(1, body.spheres.size()));
  const bool loaded = confining_stress_pa > 0.0;
  const std::size_t n = std::clamp(static_cast<std::size_t>(kProbeSpheres / per_body),
                                   loaded ? kMinLoadedBodies : kMinBodies, kMaxBodies);
  double reach = 0.0;
  for (const SphereDef& s : body.spheres) reach = std::max(reach, s.offset_m.norm() + s.radius_m);
  const double rho = physics.materials[body.material].density_kg_m3;
  const double volume = body.mass_kg / rho;
  // A square box six seed lengths wide; the region tall enough for n bodies at the fraction above.
  const double side = 12.0 * reach;
  const double height =
      std::max(4.0 * reach, static_cast<double>(n) * volume / (kRegionSolidFraction * side * side));
  const double g0 = kGravityFactor * physics.gravity_m_s2.norm();
  const double want_steps = kFallAndSettle * std::sqrt(2.0 * height / std::max(g0, 1e-9)) / dt_s;
  const double fall_steps = std::min(want_steps, std::max(kMaxFallSteps, kMaxFallSphereSteps / (static_cast<double>(n) * per_body)));
  // The fall time goes as g^(-1/2): (want / allowed)^2 more gravity fits it into the allowed steps.
  const double raise = want_steps > fall_steps ? (want_steps / fall_steps) * (want_steps / fall_steps) : 1.0;
  SimulationOptions opt;
  opt.contact = physics.contact;
  opt.gravity_m_s2 = raise * kGravityFactor * physics.gravity_m_s2;
  opt.dt_s = dt_s;
  opt.threads = threads;
  opt.seed = 1;
  Simulation sim(InteractionTable(physics.materials, physics.interactions), opt);
  Wall box;
  box.name = "probe box";
  box.shape = std::make_shared<BoxShape>(Vec3(side, side, 2.0 * height), true);
  box.material = body.material;
  sim.add_wall(box);
  FactorySpec fs;
  fs.body = body;
  fs.count = n;
  fs.region.lo_m = Vec3(reach, reach, reach);
  fs.region.hi_m = Vec3(side - reach, side - reach, height);
  const double cpu0 = run_cpu_seconds(threads);
  insert_particles(sim, fs);
  sim.run(static_cast<std::uint64_t>(fall_steps));
  std::shared_ptr<Servo> servo;
  std::size_t lid = 0;
  if (loaded) {
    const double top = highest_point_m(sim);
    Wall w;
    w.name = "probe lid";
    w.shape = std::make_shared<PlaneShape>(-Vec3::UnitZ());
    w.material = body.material;
    w.pose.origin_m = Vec3(0.5 * side, 0.5 * side, top + kLidClearance_m);
    servo = Servo::for_stress(-Vec3::UnitZ(), confining_stress_pa, side * side, kLidSpeed_m_s);
    w.motion = servo;
    lid = sim.add_wall(w);
    for (std::uint64_t s = 0; s < kMaxLoadSteps && sim.failure().status == RunStatus::ok; s += kLoadCheckSteps) {
      sim.run(kLoadCheckSteps);
      if (std::abs(servo->measured_stress_pa(sim.walls()[lid]) / confining_stress_pa - 1.0) < kLoadTolerance) break;
    }
  }
  const double cpu1 = run_cpu_seconds(threads);
  double stress_sum = 0.0;
  for (std::uint64_t s = 0; s < kTimedSteps; ++s) {
    sim.step();
    if (servo) stress_sum += servo->measured_stress_pa(sim.walls()[lid]);
  }
  const double cpu2 = run_cpu_seconds(threads);
  res.confining_stress_pa = confining_stress_pa;
  if (servo) res.measured_stress_pa = stress_sum / static_cast<double>(kTimedSteps);
  res.bodies = sim.bodies().size();
  res.spheres = sim.spheres().size();
  res.timed_steps = kTimedSteps;
  res.probe_cpu_s = cpu2 - cpu0;
  if (res.spheres > 0) res.cpu_s_per_sphere_step = (cpu2 - cpu1) / (static_cast<double>(res.spheres) * static_cast<double>(kTimedSteps));
  return res;
}

}  // namespace seedcal
