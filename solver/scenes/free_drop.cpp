#include "solver/scenes/free_drop.hpp"

#include <algorithm>
#include <chrono>
#include <limits>

#include "solver/core/random_rotation.hpp"
#include "solver/scenes/seed_bed.hpp"
#include "solver/walls/wall.hpp"

namespace seedcal {
namespace {

// The protocol's phases, named once for its plan and its run (metrics.json `phases` beside
// `plan.phases`).
constexpr const char* kPhaseDrop = "drop";

// The step for the body `b` (placed) dropped from the spec's height: the stable limit at the
// impact speed sqrt(2 g h) (scene_common.hpp).
double drop_time_step(const FreeDropSpec& spec, const BodyDef& b, SimulationOptions opt) {
  opt.dt_s = 1.0;
  Simulation probe(InteractionTable(spec.physics.materials, spec.physics.interactions), opt);
  probe.add_body(b);
  const double v_impact = std::sqrt(2.0 * spec.physics.gravity_m_s2.norm() * spec.drop_height_m);
  return choose_time_step(spec.time_step, time_step_limits(probe, v_impact));
}

}  // namespace

RunPlan plan_free_drop(const FreeDropSpec& spec) {
  SimulationOptions opt;
  opt.contact = spec.physics.contact;
  opt.gravity_m_s2 = spec.physics.gravity_m_s2;
  BodyDef b = spec.body;
  b.position_m = Vec3(0.0, 0.0, spec.drop_height_m + 1.0);  // far above the plate: only its limits count
  RunPlan p;
  p.dt_s = drop_time_step(spec, b, opt);
  p.body = spec.body;
  p.physics = spec.physics;
  p.seeds = 1.0;
  p.spheres = static_cast<double>(spec.body.spheres.size());
  // The fall, the impact and the rise to the rebound apex: at most twice the fall time.
  const double fall = std::sqrt(2.0 * spec.drop_height_m / spec.physics.gravity_m_s2.norm());
  p.phases.push_back({kPhaseDrop, std::min(spec.max_time_s, 2.0 * fall), p.spheres, true});
  return p;
}

FreeDropResult run_free_drop(const FreeDropSpec& spec) {
  const auto wall_t0 = std::chrono::steady_clock::now();
  const double cpu0 = run_cpu_seconds(spec.threads);
  FreeDropResult res;

  SimulationOptions opt;
  opt.contact = spec.physics.contact;
  opt.gravity_m_s2 = spec.physics.gravity_m_s2;
  opt.threads = 1;  // one body: threads would only add overhead
  opt.seed = spec.seed;
  opt.track_body_contacts = true;
  opt.dt_s = 1.0;
  Simulation sim(InteractionTable(spec.physics.materials, spec.physics.interactions), opt);

  BodyDef b = spec.body;
  if (spec.random_orientation) b.orientation = uniform_random_rotation(sim.rng());
  res.orientation = b.orientation;
  // Place the lowest point of the clump drop_height_m above the plate z = 0.
  double lowest = std::numeric_limits<double>::infinity();
  for (const SphereDef& s : b.spheres) lowest = std::min(lowest, (b.orientation * s.offset_m).z() - s.radius_m);
  const double com_at_touch = -lowest;
  b.position_m = Vec3(0.0, 0.0, com_at_touch + spec.drop_height_m);
  b.velocity_m_s.setZero();
  b.angular_velocity_rad_s.setZero();

  const double g = spec.physics.gravity_m_s2.norm();
  opt.dt_s = drop_time_step(spec, b, opt);
  opt.observer = spec.observer;
  Simulation run(InteractionTable(spec.physics.materials, spec.physics.interactions), opt);
  run.add_body(b);
  Wall plate;
  plate.name = "plate";
  plate.shape = std::make_shared<PlaneShape>(Vec3::UnitZ());
  plate.material = spec.plate_material;
  run.add_wall(std::move(plate));

  enum class Phase { falling, impact, rising } phase = Phase::falling;
  double apex = -std::numeric_limits<double>::infinity();
  res.run.stop_reason = "max_time_s reached before the rebound apex";
  const auto max_steps = static_cast<std::uint64_t>(spec.max_time_s / opt.dt_s);
  // Impact speed: the velocity at the end of the last step before the first touch. The velocity at
  // the end of the first touching step already holds up to a whole step of contact force (at 10
  // steps per contact and e = 0.01 that is 12 % of the speed), so it would understate the impact
  // speed and overstate the restitution.
  double vz_before_touch = 0.0;
  const double e_release = b.mass_kg * g * spec.drop_height_m;
  // At rest: kinetic energy below 1e-6 of the release energy (1e-3 of the impact speed) for 10 ms,
  // a hundred contact times of a seed on steel.
  constexpr double kRestEnergyRatio = 1e-6, kRestTime_s = 0.01;
  double rest_since_s = -1.0;
  begin_phase(res.run, run, kPhaseDrop);
  for (std::uint64_t s = 0; s < max_steps; ++s) {
    vz_before_touch = run.bodies().velocity_m_s[0].z();
    if (!run.step()) {
      res.run.failure = run.failure();
      res.run.stop_reason = std::string("guard: ") + to_string(run.failure().status);
      break;
    }
    const auto& B = run.bodies();
    const double ke = run.kinetic_energy_j();
    const double e_now = ke + B.mass_kg[0] * g * (B.position_m[0].z() - com_at_touch);
    if (e_release > 0.0) res.max_energy_ratio = std::max(res.max_energy_ratio, e_now / e_release);
    const int touching = run.stats().max_body_contacts;
    if (phase == Phase::falling && touching > 0) {
      phase = Phase::impact;
      res.impact_speed_m_s = -vz_before_touch;
    }
    if (phase == Phase::impact) {
      res.contact_points = std::max(res.contact_points, touching);
      if (touching == 0) {
        phase = Phase::rising;
        res.rebound_speed_m_s = B.velocity_m_s[0].z();
      } else if (ke < kRestEnergyRatio * e_release) {
        // A dead impact (low restitution, a clump rocking onto its side): the body stays on the
        // plate. Resting once its kinetic energy has stayed below the threshold for kRestTime_s
        // (a moment of zero speed at the deepest point of a bounce lasts far less).
        if (rest_since_s < 0.0) rest_since_s = run.time_s();
        if (run.time_s() - rest_since_s >= kRestTime_s) {
          res.run.stop_reason = "came to rest on the plate without rebounding";
          break;
        }
      } else {
        rest_since_s = -1.0;
      }
    }
    if (phase == Phase::rising) {
      apex = std::max(apex, B.position_m[0].z());
      if (B.velocity_m_s[0].z() <= 0.0 || run.stats().max_body_contacts > 0) {
        res.run.stop_reason = "apex of the first rebound reached";
        break;
      }
    }
  }
  if (res.run.failure.status == RunStatus::ok && !run.final_check()) {
    res.run.failure = run.failure();
    res.run.stop_reason = std::string("guard: ") + to_string(run.failure().status);
  }
  res.rebound_height_m = phase == Phase::rising ? std::max(0.0, apex - com_at_touch) : 0.0;
  end_phase(res.run, run);
  res.run.steps = run.step_count();
  res.run.deepest_overlap_fraction = run.deepest_overlap_fraction();
  res.run.bodies = 1;
  res.run.spheres = run.spheres().size();
  res.run.dt_s = opt.dt_s;
  res.run.cpu_seconds = run_cpu_seconds(spec.threads) - cpu0;
  res.run.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_t0).count();
  return res;
}

}  // namespace seedcal
