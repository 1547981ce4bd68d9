#include "solver/scenes/impact.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "solver/scenes/seed_bed.hpp"

namespace seedcal {
namespace {

// The protocol's phases, named once for its plan and its run (metrics.json `phases` beside
// `plan.phases`).
constexpr const char* kPhaseImpact = "impact";

// The stable limit for the scene's bodies at the expected impact speed: the largest relative speed
// between two bodies or a body and a wall, plus what gravity adds over the run.
double impact_time_step(const ImpactSpec& spec, SimulationOptions opt) {
  opt.dt_s = 1.0;
  Simulation probe(InteractionTable(spec.physics.materials, spec.physics.interactions), opt);
  for (const BodyDef& b : spec.bodies) probe.add_body(b);
  double v_exp = 0.0;
  for (std::size_t i = 0; i < spec.bodies.size(); ++i) {
    v_exp = std::max(v_exp, spec.bodies[i].velocity_m_s.norm());
    for (std::size_t j = i + 1; j < spec.bodies.size(); ++j)
      v_exp = std::max(v_exp, (spec.bodies[i].velocity_m_s - spec.bodies[j].velocity_m_s).norm());
  }
  v_exp += spec.physics.gravity_m_s2.norm() * spec.duration_s;
  return choose_time_step(spec.time_step, time_step_limits(probe, v_exp));
}

}  // namespace

RunPlan plan_impact(const ImpactSpec& spec) {
  SimulationOptions opt;
  opt.contact = spec.physics.contact;
  opt.gravity_m_s2 = spec.physics.gravity_m_s2;
  RunPlan p;
  p.dt_s = impact_time_step(spec, opt);
  p.seeds = static_cast<double>(spec.bodies.size());
  for (const BodyDef& b : spec.bodies) p.spheres += static_cast<double>(b.spheres.size());
  if (!spec.bodies.empty()) p.body = spec.bodies.front();
  p.physics = spec.physics;
  p.phases.push_back({kPhaseImpact, spec.duration_s, p.spheres, false});
  return p;
}

ImpactResult run_impact(const ImpactSpec& spec, const StepObserver& observer) {
  const auto wall_t0 = std::chrono::steady_clock::now();
  const double cpu0 = run_cpu_seconds(spec.threads);

  SimulationOptions opt;
  opt.contact = spec.physics.contact;
  opt.gravity_m_s2 = spec.physics.gravity_m_s2;
  opt.threads = spec.threads;
  opt.seed = spec.seed;
  opt.track_body_contacts = true;
  opt.dt_s = impact_time_step(spec, opt);
  opt.observer = spec.observer;

  Simulation sim(InteractionTable(spec.physics.materials, spec.physics.interactions), opt);
  for (const BodyDef& b : spec.bodies) sim.add_body(b);
  for (const ImpactWallSpec& w : spec.walls) {
    Wall wall;
    wall.name = "plane";
    wall.shape = std::make_shared<PlaneShape>(w.normal);
    wall.material = w.material;
    wall.pose.origin_m = w.point_m;
    sim.add_wall(std::move(wall));
  }

  ImpactResult res;
  const auto steps = static_cast<std::uint64_t>(std::llround(spec.duration_s / opt.dt_s));
  bool in_first_impact = false, first_impact_done = false;
  res.run.stop_reason = "duration reached";
  begin_phase(res.run, sim, kPhaseImpact);
  for (std::uint64_t s = 0; s < steps; ++s) {
    if (!sim.step()) {
      res.run.failure = sim.failure();
      res.run.stop_reason = std::string("guard: ") + to_string(sim.failure().status);
      break;
    }
    const StepStats& st = sim.stats();
    const std::size_t touching = st.sphere_contacts + st.wall_contacts;
    if (!first_impact_done) {
      if (touching > 0 && !in_first_impact) {
        in_first_impact = true;
        res.first_touch_s = sim.time_s() - opt.dt_s;  // contact began during this step
      } else if (touching == 0 && in_first_impact) {
        in_first_impact = false;
        first_impact_done = true;
        res.contact_duration_s = (sim.time_s() - opt.dt_s) - res.first_touch_s;
      }
    }
    res.max_overlap_m = std::max(res.max_overlap_m, st.max_overlap_m);
    res.max_normal_force_n = std::max(res.max_normal_force_n, st.max_normal_force_n);
    res.max_contact_points = std::max(res.max_contact_points, st.max_body_contacts);
    if (observer) observer(sim);
  }
  if (in_first_impact) res.contact_duration_s = sim.time_s() - res.first_touch_s;
  if (res.run.failure.status == RunStatus::ok && !sim.final_check()) {
    res.run.failure = sim.failure();
    res.run.stop_reason = std::string("guard: ") + to_string(sim.failure().status);
  }

  const BodyState& B = sim.bodies();
  for (std::uint32_t id = 0; id < B.size(); ++id) {  // input order, whatever the storage order
    const std::uint32_t b = sim.index_of(id);
    res.final_states.push_back({B.position_m[b], B.velocity_m_s[b], B.angular_velocity[b]});
  }
  end_phase(res.run, sim);
  res.run.steps = sim.step_count();
  res.run.deepest_overlap_fraction = sim.deepest_overlap_fraction();
  res.run.bodies = B.size();
  res.run.spheres = sim.spheres().size();
  res.run.dt_s = opt.dt_s;
  res.run.cpu_seconds = run_cpu_seconds(spec.threads) - cpu0;
  res.run.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_t0).count();
  return res;
}

}  // namespace seedcal
