#include "solver/sim/simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "solver/integrate/velocity_verlet.hpp"
#include "solver/sim/contact_forces.hpp"
#include "solver/sim/overlap_limits.hpp"
#include "solver/sim/phase_clock.hpp"
#include "solver/sim/work_split.hpp"
#include "solver/sim/time_step.hpp"

namespace seedcal {

const char* to_string(RunStatus s) {
  switch (s) {
    case RunStatus::ok: return "ok";
    case RunStatus::non_finite: return "non_finite";
    case RunStatus::energy_runaway: return "energy_runaway";
    case RunStatus::deep_overlap: return "deep_overlap";
    case RunStatus::aborted: return "aborted";
  }
  return "unknown";
}

BodyDef sphere_body(double radius_m, double density_kg_m3, std::uint16_t material) {
  BodyDef d;
  d.spheres.push_back({Vec3::Zero(), radius_m});
  d.material = material;
  d.mass_kg = density_kg_m3 * 4.0 / 3.0 * std::numbers::pi * radius_m * radius_m * radius_m;
  d.principal_inertia_kg_m2 = Vec3::Constant(0.4 * d.mass_kg * radius_m * radius_m);
  return d;
}

Simulation::Simulation(InteractionTable table, SimulationOptions options)
    : table_(std::move(table)), options_(options), rng_(options.seed) {
  validate_options(options_);
  if (options_.observer.on_frame) next_frame_s_ = 0.0;
  if (options_.observer.on_progress) next_progress_s_ = options_.observer.progress_interval_s;
  bodies_.first_sphere.push_back(0);
}

std::uint32_t Simulation::add_body(const BodyDef& def) {
  if (def.spheres.empty()) throw std::invalid_argument("add_body: a body needs at least one sphere");
  if (!(def.mass_kg > 0.0)) throw std::invalid_argument("add_body: mass must be > 0");
  require_interactions(def.material, false, "add_body");
  settle();
  const auto b = static_cast<std::uint32_t>(bodies_.size());
  bodies_.position_m.push_back(def.position_m);
  bodies_.orientation.push_back(def.orientation.normalized());
  bodies_.velocity_m_s.push_back(def.velocity_m_s);
  const Vec3& I = def.principal_inertia_kg_m2;
  const bool iso = std::abs(I.x() - I.y()) <= 1e-12 * I.x() && std::abs(I.x() - I.z()) <= 1e-12 * I.x();
  // 2: a lone sphere at the centre of mass, whose orientation moves nothing (move_bodies).
  const bool lone = def.spheres.size() == 1 && def.spheres.front().offset_m.isZero(0.0);
  bodies_.isotropic.push_back(iso ? (lone ? 2 : 1) : 0);
  bodies_.principal_inertia.push_back(I);
  bodies_.inv_inertia.push_back(I.cwiseInverse());
  bodies_.angular_momentum.push_back(
      angular_momentum_from_velocity(bodies_.orientation.back(), I, def.angular_velocity_rad_s));
  bodies_.angular_velocity.push_back(def.angular_velocity_rad_s);
  bodies_.mass_kg.push_back(def.mass_kg);
  bodies_.inv_mass.push_back(1.0 / def.mass_kg);
  bodies_.id.push_back(b);
  index_of_id_.push_back(b);
  bodies_.force_n.push_back(Vec3::Zero());
  bodies_.torque_n_m.push_back(Vec3::Zero());
  for (const SphereDef& sd : def.spheres) {
    spheres_.body.push_back(b);
    spheres_.offset_body_m.push_back(sd.offset_m);
    spheres_.radius_m.push_back(sd.radius_m);
    spheres_.material.push_back(def.material);
    spheres_.position_m.push_back(def.position_m + bodies_.orientation.back() * sd.offset_m);
  }
  bodies_.first_sphere.push_back(static_cast<std::uint32_t>(spheres_.size()));
  if (body_materials_.size() <= def.material) body_materials_.resize(def.material + 1u, 0);
  body_materials_[def.material] = 1;
  ready_ = false;
  reference_energy_j_ = -1.0;
  return b;
}

std::size_t Simulation::add_wall(Wall wall) {
  if (!wall.shape) throw std::invalid_argument("add_wall: wall '" + wall.name + "' has no shape");
  require_interactions(wall.material, true, "add_wall: wall '" + wall.name + "'");
  if (wall_materials_.size() <= wall.material) wall_materials_.resize(wall.material + 1u, 0);
  wall_materials_[wall.material] = 1;
  walls_.push_back(std::move(wall));
  ready_ = false;
  return walls_.size() - 1;
}

void Simulation::require_interactions(std::uint16_t material, bool wall, const std::string& what) const {
  const std::size_t n = table_.material_count();
  if (material >= n)
    throw std::invalid_argument(what + ": material index " + std::to_string(material) + " is not in the table (" +
                                std::to_string(n) + " materials)");
  const auto& mats = table_.materials();
  auto check = [&](const std::vector<char>& present, const char* other) {
    for (std::size_t m = 0; m < present.size(); ++m) {
      if (!present[m] || table_.pair(material, static_cast<std::uint16_t>(m)).defined) continue;
      throw std::invalid_argument(what + ": materials '" + mats[material].name + "' and '" + mats[m].name +
                                  "' have no interaction, and a " + other +
                                  " of the second can touch it: they would pass through each other "
                                  "with zero force");
    }
  };
  check(body_materials_, "body");
  if (!wall) check(wall_materials_, "wall");
}

void Simulation::set_time_step(double dt_s) {
  require_time_step(dt_s, "set_time_step");
  options_.dt_s = dt_s;
}

void Simulation::set_body_motion(std::uint32_t b, const Vec3& v, const Vec3& w) {
  settle();
  bodies_.velocity_m_s[b] = v;
  bodies_.angular_velocity[b] = w;
  bodies_.angular_momentum[b] =
      angular_momentum_from_velocity(bodies_.orientation[b], bodies_.principal_inertia[b], w);
  // Running: the guard needs the new reference now (ensure_ready() takes it before the first step).
  reference_energy_j_ = -1.0;
  if (ready_) take_energy_reference();
}

void Simulation::take_energy_reference() {
  reference_energy_j_ = energy_budget_j();
  reference_potential_j_ = potential_energy_j();
  wall_work_j_ = 0.0;
}

double Simulation::rayleigh_time_step_s() const {
  double dt = std::numeric_limits<double>::infinity();
  const auto& mats = table_.materials();
  for (std::size_t i = 0; i < spheres_.size(); ++i) {
    const Material& m = mats[spheres_.material[i]];
    dt = std::min(dt, seedcal::rayleigh_time_step_s(spheres_.radius_m[i], m.density_kg_m3,
                                           m.shear_modulus_pa(), m.poisson_ratio));
  }
  return dt;
}

ContactInputs Simulation::contact_inputs() const {
  return {options_, table_, bodies_, spheres_, walls_};
}

void Simulation::ensure_ready() {
  if (ready_) return;
  settle();
  double r_max = 0.0;
  for (double r : spheres_.radius_m) r_max = std::max(r_max, r);
  contacts_.skin_m = options_.skin_m > 0.0 ? options_.skin_m : 0.2 * r_max;
  contacts_.pairs.set_search(options_.pair_search);
  threads_.size(options_.threads, bodies_.size(), walls_.size());
  place_spheres(bodies_, spheres_, options_.threads);
  rebuild_lists();
  ready_ = true;
  compute_forces(false);
  if (reference_energy_j_ < 0.0) take_energy_reference();
}

void Simulation::rebuild_lists() {
  // Rolling-spring history exists only for EPSD: no rolling history when it is not needed.
  contacts_.rebuild(spheres_, walls_, options_.contact.rolling == RollingModel::epsd,
                    options_.threads);
  contacts_.overlap_limit_m =
      sphere_overlap_limits(bodies_, spheres_, table_.materials(), options_.guards);
}

void Simulation::update_work_shares() {
  threads_.update_shares(contacts_.lists_version, options_.threads, bodies_, spheres_,
                         contacts_.pairs, contacts_.wall_pairs);
}

void Simulation::finish_kick() {
  if (!kick_pending_) return;
  finish_half_kick(bodies_, 0.5 * kick_dt_s_, options_.threads);
  kick_pending_ = false;
}

// One step: the first half of velocity Verlet for every body (with the last step's pending
// second half kick), the walls' motion, the neighbour lists when the skin is used up, the contact
// forces, their reduction to the bodies, the guards. The threads stay in one parallel region from
// the body pass to the force reduction, meeting at two barriers (every view written before any
// contact is computed; every contact before any body's forces are summed), unless the lists must
// be rebuilt or the bodies re-sorted this step; then the region ends after the body pass and the
// forces take a region of their own. Each thread moves, and sums the forces of, fixed ranges of
// bodies (sim/work_split.hpp), so the results do not depend on which path a step takes or on the
// timing of the threads.
bool Simulation::step() {
  if (failure_.status != RunStatus::ok) return false;
  ensure_ready();
  if (time_s_ >= next_frame_s_) emit_frame();
  if (time_s_ >= next_progress_s_) {
    next_progress_s_ = time_s_ + options_.observer.progress_interval_s;
    options_.observer.on_progress(*this);
  }
  const double dt = options_.dt_s;
  const bool prof = options_.profile;
  auto t0 = prof ? std::chrono::steady_clock::now() : std::chrono::steady_clock::time_point{};
  const std::size_t nb = bodies_.size(), ns = spheres_.size();
  const int nt = std::max(1, options_.threads);
  update_work_shares();
  const std::vector<WorkShare>& shares = threads_.shares;
  // Small worlds stay in the cache unsorted; a world of few bodies with many spheres each (fine
  // clumps) is sorted too, so that each thread's slab holds its own bodies.
  const bool sort_due = options_.sort_interval_steps > 0 && (step_ + 1) % options_.sort_interval_steps == 0 &&
                        (nb >= 512 || ns >= 8192);
  // The previous step's second half kick, when pending, with that step's dt (finish_kick()).
  VerletPass pass;
  pass.dt_s = dt;
  pass.kick = kick_pending_;
  pass.kick_half_s = 0.5 * kick_dt_s_;
  pass.predict_s = options_.contact.dashpot_predicted ? 0.5 * dt : 0.0;
  kick_pending_ = false;
  contacts_.body_view.resize(nb);
  contacts_.sphere_view.resize(ns);
  BodyView* body_view = contacts_.body_view.data();
  SphereView* sphere_view = contacts_.sphere_view.data();
  // Skin check against the centres at the last neighbour build (none after a renumbering).
  const std::vector<Vec3>& built = contacts_.pairs.built_at();
  const Vec3* ref = built.size() == ns ? built.data() : nullptr;
  // Valid for this step's forces unless the lists are rebuilt (then compute_forces() sets them up
  // again).
  prepare_forces();
  threads_.start_step(nt);
  bool walls_moved = false, rebuild = false;
  std::int64_t force_bad = std::numeric_limits<std::int64_t>::max();
#pragma omp parallel num_threads(nt) if (nt > 1) reduction(min : force_bad)
  {
    const int t = omp_get_thread_num(), team = omp_get_num_threads();
    double moved_sq = 0.0;
    std::int64_t bad = std::numeric_limits<std::int64_t>::max();
    for (std::size_t sh = static_cast<std::size_t>(t); sh < shares.size();
         sh += static_cast<std::size_t>(team))
      move_bodies(bodies_, spheres_, body_view, sphere_view, shares[sh].move_begin,
                  shares[sh].move_end, pass, ref, moved_sq, bad);
    threads_.moved_sq[static_cast<std::size_t>(t)] = moved_sq;
    threads_.bad[static_cast<std::size_t>(t)] = bad;
    if (t == 0) {
      for (Wall& w : walls_)
        if (w.motion) w.motion->advance(w, time_s_, dt);
      time_s_ += dt;
      ++step_;
      walls_moved = contacts_.walls_moved_beyond_skin(walls_);
    }
#pragma omp barrier
    // Every thread reaches the same decision from the same values.
    double moved_all_sq = 0.0;
    for (double m : threads_.moved_sq) moved_all_sq = std::max(moved_all_sq, m);
    const bool rebuild_now =
        ref == nullptr || moved_all_sq > contacts_.pairs.rebuild_distance_sq();
    if (t == 0) {
      rebuild = rebuild_now;
      lap(prof, t0, profile_.integrate_s);
    }
    if (!rebuild_now && !walls_moved && !sort_due) forces_in_region(t, team, dt, t0, force_bad);
  }
  std::int64_t first_bad = -1;
  if (rebuild || walls_moved || sort_due) {
    if (sort_due && sort_spatially()) {
      contacts_.refresh_views(bodies_, spheres_, pass.predict_s, options_.threads);
      rebuild = false;  // the renumbering rebuilt the lists
    }
    if (rebuild || contacts_.walls_moved_beyond_skin(walls_)) rebuild_lists();
    lap(prof, t0, profile_.neighbour_s);
    // Forces at t_{n+1}; their second half kick is left pending (finish_kick()).
    first_bad = compute_forces(true);
  } else {
    first_bad = finish_forces(true, force_bad);
    lap(prof, t0, profile_.reduce_s);
  }
  std::int64_t moved_bad = std::numeric_limits<std::int64_t>::max();
  for (std::int64_t b : threads_.bad) moved_bad = std::min(moved_bad, b);
  if (moved_bad != std::numeric_limits<std::int64_t>::max() &&
      (first_bad < 0 || moved_bad < first_bad))
    first_bad = moved_bad;
  if (first_bad >= 0 && failure_.status == RunStatus::ok) {
    const std::string step_note = step_size_note();
    fail(RunStatus::non_finite, first_bad,
         "position or velocity is not finite; likely cause: " +
             (step_note.empty() ? std::string("time step above the stable limit for the stiffest "
                                              "contact (lower dt_s or rayleigh_fraction)")
                                : step_note));
    return false;
  }
  return check_guards();
}

bool Simulation::run(std::uint64_t n) {
  for (std::uint64_t i = 0; i < n; ++i)
    if (!step()) return false;
  return true;
}

double Simulation::kinetic_energy_j() const {
  settle();
  double e = 0.0;
  for (std::size_t b = 0; b < bodies_.size(); ++b)
    e += 0.5 * bodies_.mass_kg[b] * bodies_.velocity_m_s[b].squaredNorm() +
         0.5 * bodies_.angular_momentum[b].dot(bodies_.angular_velocity[b]);
  return e;
}

// Gravitational potential energy -sum m g.x (world origin as reference), J.
double Simulation::potential_energy_j() const {
  double e = 0.0;
  for (std::size_t b = 0; b < bodies_.size(); ++b)
    e -= bodies_.mass_kg[b] * options_.gravity_m_s2.dot(bodies_.position_m[b]);
  return e;
}

// Energy the scene can supply beyond its potential energy and the walls' work: the kinetic energy
// at the start, the kinetic energy every body would have at the fastest moving wall's speed, and a
// floor of each body falling one largest-sphere diameter (so a resting bed has a non-zero budget;
// it also covers the elastic energy of a bed resting under gravity, whose overlaps are a small
// fraction of a radius). The guard compares the kinetic energy, less the potential energy released
// and the work the walls did since the reference (wall_work_j()), with a multiple of it. By the
// energy balance KE + U + D = KE0 + U0 + W + released (U the contacts' elastic energy, D >= 0 what
// the dashpots and friction dissipated) only a numerical error can carry it past KE0 + U0: a
// force chain that a servo lid loaded and that buckles gives back the lid's work, not more.
double Simulation::energy_budget_j() const {
  double m_total = 0.0, r_max = 0.0;
  for (double m : bodies_.mass_kg) m_total += m;
  for (double r : spheres_.radius_m) r_max = std::max(r_max, r);
  double v_wall = 0.0;
  for (const Wall& w : walls_)
    if (w.motion) v_wall = std::max(v_wall, w.motion->max_speed_m_s(1.0));
  return kinetic_energy_j() + 0.5 * m_total * v_wall * v_wall +
         m_total * std::max(options_.gravity_m_s2.norm(), 1.0) * 2.0 * r_max;
}

// A guard message's hint when the step itself is the likely cause: above the Rayleigh step of the
// smallest sphere (sim/time_step.hpp) no explicit DEM step is stable for resting contacts.
std::string Simulation::step_size_note() const {
  const double dt_r = rayleigh_time_step_s();
  if (!(options_.dt_s > dt_r)) return "";
  std::ostringstream m;
  m.precision(3);
  m << "the time step dt_s = " << options_.dt_s << " s is " << options_.dt_s / dt_r
    << " x the Rayleigh step of the smallest sphere (" << dt_r
    << " s): lower dt_s or rayleigh_fraction (docs/time_step.md)";
  return m.str();
}

void Simulation::fail(RunStatus s, std::int64_t body, std::string message) {
  failure_.status = s;
  failure_.step = step_;
  failure_.time_s = time_s_;
  failure_.body = body;
  std::ostringstream m;
  m << "step " << step_ << " (t = " << time_s_ << " s)";
  if (body >= 0) m << ", body " << body;
  m << ": " << message;
  failure_.message = m.str();
  if (log_) log_(failure_.message);
  if (options_.observer.on_frame && last_frame_step_ != step_) emit_frame();
}

void Simulation::emit_frame() {
  const double dt_frame = options_.observer.interval_s;
  last_frame_step_ = step_;
  // The next multiple of the interval after now. The slack of 1e-6 intervals absorbs the rounding
  // of a time summed step by step (0.01 may arrive as 0.00999999999), so a frame is not a step late.
  constexpr double kSlack = 1e-6;
  next_frame_s_ = (std::floor(time_s_ / dt_frame + kSlack) + 1.0 - kSlack) * dt_frame;
  options_.observer.on_frame(*this);
}

bool Simulation::final_check() {
  bool ok = failure_.status == RunStatus::ok;
  if (ready_ && ok) ok = check_guards(true);  // a failure here has taken its frame in fail()
  if (options_.observer.on_frame && last_frame_step_ != step_) emit_frame();
  return ok;
}

bool Simulation::check_guards(bool energy_now) {
  if (failure_.status != RunStatus::ok) return false;
  const std::size_t nb = bodies_.size();
  const int every = std::max(1, options_.guards.check_interval);
  if (energy_now || step_ % static_cast<std::uint64_t>(every) == 0) {
    const double ke = kinetic_energy_j();
    const double released = reference_potential_j_ - potential_energy_j();
    const double limit = options_.guards.max_energy_factor * reference_energy_j_;
    if (ke - released - wall_work_j_ > limit) {
      std::size_t worst = 0;
      double worst_e = -1.0;
      for (std::size_t b = 0; b < nb; ++b) {
        const double e = bodies_.mass_kg[b] * bodies_.velocity_m_s[b].squaredNorm();
        if (e > worst_e) { worst_e = e; worst = b; }
      }
      std::ostringstream m;
      m << "kinetic energy " << ke << " J, less the potential energy released (" << released
        << " J) and the work the walls did (" << wall_work_j_ << " J), exceeds "
        << options_.guards.max_energy_factor
        << " x the energy the scene can supply (" << reference_energy_j_
        << " J); likely cause: "
        << (step_size_note().empty()
                ? std::string("time step above the stable limit (lower dt_s) or interpenetrating "
                              "initial positions")
                : step_size_note());
      fail(RunStatus::energy_runaway, static_cast<std::int64_t>(worst), m.str());
      return false;
    }
  }
  return failure_.status == RunStatus::ok;
}

}  // namespace seedcal
