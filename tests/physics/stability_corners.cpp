#include "tests/physics/stability_corners.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "solver/core/errors.hpp"
#include "solver/scenes/bulk_density.hpp"
#include "solver/scenes/free_drop.hpp"
#include "solver/scenes/impact.hpp"
#include "solver/sim/time_step.hpp"
#include "tests/support/cli.hpp"

namespace seedcal::stability {

const char* to_string(Shape s) {
  switch (s) {
    case Shape::sphere: return "sphere r 4 mm";
    case Shape::seed9: return "9-sphere seed";
    case Shape::ratio20: return "1:20 bumps";
    case Shape::spheres2000: return "2000 spheres";
  }
  return "?";
}

const char* to_string(Verdict v) {
  switch (v) {
    case Verdict::ok: return "ok";
    case Verdict::refused: return "refused";
    case Verdict::stopped: return "stopped";
    case Verdict::energy_gain: return "energy_gain";
    case Verdict::bad_index: return "bad_index";
  }
  return "?";
}

std::vector<SphereXYZR> shape_spheres(Shape s) {
  std::vector<SphereXYZR> out;
  switch (s) {
    case Shape::sphere:
      out.push_back({Vec3::Zero(), 0.004});
      break;
    case Shape::seed9: {
      const std::string path = testing::source_dir() + "/data/bench/clump9.txt";
      std::ifstream in(path);
      std::string line;
      while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream row(line);
        double x = 0, y = 0, z = 0, r = 0;
        if (row >> x >> y >> z >> r) out.push_back({Vec3(x, y, z), r});
      }
      if (out.empty()) throw std::runtime_error("cannot read " + path);
      break;
    }
    case Shape::ratio20:
      out.push_back({Vec3::Zero(), 0.004});
      for (int axis = 0; axis < 3; ++axis)
        for (double sign : {-1.0, 1.0}) {
          Vec3 c = Vec3::Zero();
          c[axis] = sign * 0.0039;  // bump of 0.2 mm, its outer point 0.1 mm beyond the sphere
          out.push_back({c, 0.0002});
        }
      break;
    case Shape::spheres2000:
      for (int i = 0; i < 10; ++i)
        for (int j = 0; j < 10; ++j)
          for (int k = 0; k < 20; ++k)
            out.push_back({Vec3(0.0007 * i, 0.0007 * j, 0.0007 * k), 0.0005});
      break;
  }
  return out;
}

namespace {

// Material 0: the particle; 1: steel (Table 6). Both pairs get the corner's coefficients.
PhysicsSpec physics(const Corner& c, bool gravity) {
  PhysicsSpec p;
  p.materials = {{"particle", c.density_kg_m3, c.youngs_modulus_pa, c.poisson_ratio},
                 {"steel", 7850.0, 2.0e10, 0.3}};
  p.interactions = {
      {"particle_particle", 0, 0, c.restitution, c.static_friction, c.rolling_friction},
      {"particle_steel", 0, 1, c.restitution, c.static_friction, c.rolling_friction}};
  p.contact.normal = c.normal;
  p.contact.rolling = c.rolling;
  p.contact.dashpot_predicted = c.dashpot_predicted;
  p.gravity_m_s2 = gravity ? Vec3(0.0, 0.0, -9.81) : Vec3::Zero();
  return p;
}

TimeStepSpec step_spec(StepChoice s) {
  TimeStepSpec t;
  t.dt_s = s.dt_s;
  if (s.fraction > 0.0) {
    t.rayleigh_fraction = s.fraction;
    t.rayleigh_fraction_set = true;
  }
  t.force_dt = s.force;
  return t;
}

// The shape's body with its principal frame at the origin; mass properties of the union of the
// spheres (clump/mass_properties.hpp) to a relative tolerance of 1e-3 (the default 1e-4 takes 8 s
// for 2,000 spheres, 1e-3 0.2 s; the mass differs by 1.3e-4). Cached per shape and density.
const BodyDef& shape_body(Shape s, double density_kg_m3) {
  struct Entry {
    Shape shape;
    double density;
    BodyDef body;
  };
  static std::vector<Entry> cache;
  for (const Entry& e : cache)
    if (e.shape == s && e.density == density_kg_m3) return e.body;
  cache.push_back({s, density_kg_m3,
                   clump_body(shape_spheres(s), density_kg_m3, 0, Vec3::Zero(), Quat::Identity(), 1e-3)});
  return cache.back().body;
}

// Lowest point of a body's spheres below its centre for an orientation.
double depth_below_centre(const BodyDef& b, const Quat& q) {
  double lowest = std::numeric_limits<double>::infinity();
  for (const SphereDef& s : b.spheres) lowest = std::min(lowest, (q * s.offset_m).z() - s.radius_m);
  return -lowest;
}

bool finite(const Vec3& v) { return std::isfinite(v.sum()); }

// Runs a scene (`run` returns its result); a refused setting (SettingError) sets the verdict and
// returns false. Otherwise the step, step count and stop reason are copied into `o`.
template <class Result, class Run>
bool run_or_refuse(Outcome& o, Result& r, Run&& run) {
  try {
    r = run();
  } catch (const SettingError& e) {
    o.verdict = Verdict::refused;
    o.refused_key = e.key();
    o.message = e.what();
    return false;
  }
  o.dt_s = r.run.dt_s;
  o.steps = r.run.steps;
  o.stop_reason = r.run.stop_reason;
  return true;
}

// True (with the verdict set) when a guard stopped the run.
bool stopped(Outcome& o, const RunReport& r) {
  if (r.failure.status == RunStatus::ok) return false;
  o.verdict = Verdict::stopped;
  o.message = r.failure.message;
  return true;
}

// The verdict of a finished run: a bad index (`why` not empty) first, then an energy gain beyond
// the bound ("<energy> rose to X x <reference>").
void judge(Outcome& o, const std::string& why, const std::string& energy, const std::string& reference) {
  if (!why.empty()) {
    o.verdict = Verdict::bad_index;
    o.message = why;
  } else if (o.max_energy_ratio > 1.0 + kEnergyGainBound) {
    o.verdict = Verdict::energy_gain;
    o.message = energy + " rose to " + std::to_string(o.max_energy_ratio) + " x " + reference;
  }
}

}  // namespace

Outcome impact(const Corner& c, StepChoice step, double speed_m_s, double gap) {
  Outcome o;
  ImpactSpec spec;
  spec.physics = physics(c, false);
  spec.time_step = step_spec(step);
  BodyDef b = shape_body(c.shape, c.density_kg_m3);
  b.position_m = Vec3(0.0, 0.0, depth_below_centre(b, b.orientation) + gap);
  b.velocity_m_s = Vec3(0.0, 0.0, -speed_m_s);
  spec.bodies = {b};
  spec.walls = {ImpactWallSpec{Vec3::Zero(), Vec3::UnitZ(), 1}};
  // Run past the first contact: the Hertz contact time of the whole mass on the largest sphere
  // (the longest a single contact lasts), four times over, after the gap is closed.
  double r_max = 0.0;
  for (const SphereDef& s : b.spheres) r_max = std::max(r_max, s.radius_m);
  const InteractionTable table(spec.physics.materials, spec.physics.interactions);
  const double tc = hertz_impact(b.mass_kg, r_max, table.pair(0, 1).e_star_pa, speed_m_s).contact_time_s;
  spec.duration_s = gap / speed_m_s + 4.0 * tc;
  const double ke0 = 0.5 * b.mass_kg * speed_m_s * speed_m_s;
  double ke_max = 0.0;
  ImpactResult r;
  if (!run_or_refuse(o, r, [&] {
        return run_impact(spec, [&](const Simulation& sim) { ke_max = std::max(ke_max, sim.kinetic_energy_j()); });
      }))
    return o;
  o.contact_time_s = r.contact_duration_s;
  o.steps_per_contact = r.run.dt_s > 0.0 ? tc / r.run.dt_s : 0.0;
  o.max_energy_ratio = ke_max / ke0;
  o.deepest_overlap_fraction = r.run.deepest_overlap_fraction;
  if (stopped(o, r.run)) return o;
  const BodyFinalState& f = r.final_states.at(0);
  o.restitution_out = f.velocity_m_s.z() / speed_m_s;
  std::ostringstream why;
  if (!finite(f.position_m) || !finite(f.velocity_m_s) || !finite(f.angular_velocity_rad_s) ||
      !std::isfinite(r.max_overlap_m) || !std::isfinite(r.max_normal_force_n))
    why << "a final state or peak value is not finite";
  else if (!(r.contact_duration_s > 0.0) || r.max_contact_points < 1)
    why << "no contact was recorded";
  else if (c.shape == Shape::sphere && !(o.restitution_out >= 0.0 && o.restitution_out <= 1.0 + kEnergyGainBound))
    why << "restitution " << o.restitution_out << " outside [0, 1]";
  judge(o, why.str(), "kinetic energy", "the initial");
  return o;
}

Outcome free_drop(const Corner& c, StepChoice step, double drop_height_m) {
  Outcome o;
  FreeDropSpec spec;
  spec.physics = physics(c, true);
  spec.time_step = step_spec(step);
  spec.body = shape_body(c.shape, c.density_kg_m3);
  spec.plate_material = 1;
  spec.drop_height_m = drop_height_m;
  spec.random_orientation = c.shape != Shape::sphere && c.shape != Shape::ratio20;
  spec.seed = 1;
  FreeDropResult r;
  if (!run_or_refuse(o, r, [&] { return run_free_drop(spec); })) return o;
  o.max_energy_ratio = r.max_energy_ratio;
  o.restitution_out = r.impact_speed_m_s > 0.0 ? r.rebound_speed_m_s / r.impact_speed_m_s : 0.0;
  if (stopped(o, r.run)) return o;
  std::ostringstream why;
  if (!std::isfinite(r.rebound_height_m) || !std::isfinite(o.restitution_out))
    why << "rebound height or restitution not finite";
  else if (r.contact_points < 1)
    why << "no contact point recorded";
  else if (r.rebound_height_m < 0.0 || r.rebound_height_m > drop_height_m * (1.0 + kEnergyGainBound))
    why << "rebound height " << r.rebound_height_m << " m outside [0, drop height]";
  judge(o, why.str(), "energy", "the release energy");
  return o;
}

Outcome bed(const Corner& c, StepChoice step, double container_m, double max_time_s) {
  Outcome o;
  BulkDensitySpec spec;
  spec.physics = physics(c, true);
  spec.time_step = step_spec(step);
  spec.seeds.body = shape_body(c.shape, c.density_kg_m3);
  spec.wall_material = 1;
  spec.container_m = Vec3::Constant(container_m);
  spec.max_time_s = max_time_s;
  spec.seed = 1;
  BulkDensityResult r;
  if (!run_or_refuse(o, r, [&] { return run_bulk_density(spec); }) || stopped(o, r.run)) return o;
  o.restitution_out = r.solid_fraction;  // the bed's index, reported in the same slot
  // A random packing of equal spheres or seeds has a solid fraction of 0.55-0.64; a small box
  // (three seeds across) and the strike-off by centroid widen that to (0.2, 0.8).
  if (!std::isfinite(r.solid_fraction) || r.solid_fraction <= 0.2 || r.solid_fraction >= 0.8) {
    o.verdict = Verdict::bad_index;
    o.message = "solid fraction " + std::to_string(r.solid_fraction) + " outside (0.2, 0.8) (" +
                r.run.stop_reason + ", " + std::to_string(r.seeds_inside) + " seeds inside)";
  }
  return o;
}

}  // namespace seedcal::stability
