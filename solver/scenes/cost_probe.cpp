#include "solver/scenes/cost_probe.hpp"

#include <algorithm>
#include <cmath>

#include "solver/sim/particle_factory.hpp"
#include "solver/walls/box_shape.hpp"

namespace seedcal {
namespace {

// About 1,500 spheres: enough that the per-step fixed costs do not count, few enough that the
// probe costs a small part of one run of a bulk scene. At least 12 bodies so a fine clump still
// forms a bed two deep.
constexpr double kProbeSpheres = 1500.0;
constexpr std::size_t kMinBodies = 12, kMaxBodies = 400;
// The bodies are placed in a region four bed heights tall (about a quarter of it solid, where the
// factory's random placement jams) and fall under five times gravity, which brings them into a bed
// in a fifth of the time: the probe measures cost, not physics.
constexpr double kGravityFactor = 5.0;
constexpr double kRegionSolidFraction = 0.15;
constexpr std::uint64_t kTimedSteps = 1000;
constexpr double kMaxFallSteps = 20000.0;
constexpr double kMaxFlightSteps = 20000.0;

}  // namespace

CostProbe probe_sphere_step_cost(const PhysicsSpec& physics, const BodyDef& body, double dt_s, int threads,
                                 bool bed) {
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
  const std::size_t n = std::clamp(static_cast<std::size_t>(kProbeSpheres / per_body), kMinBodies, kMaxBodies);
  double reach = 0.0;
  for (const SphereDef& s : body.spheres) reach = std::max(reach, s.offset_m.norm() + s.radius_m);
  const double rho = physics.materials[body.material].density_kg_m3;
  const double volume = body.mass_kg / rho;
  // A square box six seed lengths wide; the region tall enough for n bodies at the fraction above.
  const double side = 12.0 * reach;
  const double height =
      std::max(4.0 * reach, static_cast<double>(n) * volume / (kRegionSolidFraction * side * side));
  SimulationOptions opt;
  opt.contact = physics.contact;
  opt.gravity_m_s2 = kGravityFactor * physics.gravity_m_s2;
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
  const double g = opt.gravity_m_s2.norm();
  // The fall, at most kMaxFallSteps (a stiff material's step is short; the bed is then looser).
  const double fall_steps = std::sqrt(2.0 * height / std::max(g, 1e-9)) / dt_s;
  sim.run(static_cast<std::uint64_t>(std::min(fall_steps, kMaxFallSteps)));
  const double cpu1 = run_cpu_seconds(threads);
  sim.run(kTimedSteps);
  const double cpu2 = run_cpu_seconds(threads);
  res.bodies = sim.bodies().size();
  res.spheres = sim.spheres().size();
  res.timed_steps = kTimedSteps;
  res.probe_cpu_s = cpu2 - cpu0;
  if (res.spheres > 0) res.cpu_s_per_sphere_step = (cpu2 - cpu1) / (static_cast<double>(res.spheres) * static_cast<double>(kTimedSteps));
  return res;
}

}  // namespace seedcal
