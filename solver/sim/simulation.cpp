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

#include "solver/integrate/free_rotation.hpp"
#include "solver/sim/contact_forces.hpp"
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
  if (!(options_.dt_s > 0.0)) throw std::invalid_argument("Simulation: dt_s must be > 0");
  if (options_.threads < 1) options_.threads = 1;
  if (options_.observer.on_frame) {
    if (!(options_.observer.interval_s > 0.0))
      throw std::invalid_argument("Simulation: a frame observer needs interval_s > 0");
    next_frame_s_ = 0.0;
  }
  if (options_.observer.on_progress) {
    if (!(options_.observer.progress_interval_s > 0.0))
      throw std::invalid_argument("Simulation: a progress observer needs progress_interval_s > 0");
    next_progress_s_ = options_.observer.progress_interval_s;
  }
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
  if (!(dt_s > 0.0)) throw std::invalid_argument("set_time_step: dt_s must be > 0");
  options_.dt_s = dt_s;
}

void Simulation::set_body_motion(std::uint32_t b, const Vec3& v, const Vec3& w) {
  settle();
  bodies_.velocity_m_s[b] = v;
  bodies_.angular_velocity[b] = w;
  bodies_.angular_momentum[b] =
      angular_momentum_from_velocity(bodies_.orientation[b], bodies_.principal_inertia[b], w);
  reference_energy_j_ = -1.0;
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

namespace {
// Sphere i of body b at the body's pose (world centre): x_b + R(q) offset_i. The rotation matrix
// is formed once per body (sphere_rotation) and applied to each of its spheres: for a clump that
// is 15 flops per sphere against about 30 for rotating by the quaternion itself.
inline Mat3 sphere_rotation(const Quat& q) { return q.toRotationMatrix(); }
inline Vec3 sphere_centre(const Vec3& body_position, const Mat3& rotation, const Vec3& offset) {
  return offset.isZero(0.0) ? body_position : Vec3(body_position + rotation * offset);
}

// Body b's translation and momentum for a step: the last step's second half kick when pending
// (the same operations as finish_kick()), then velocity Verlet's first half: kick with the same
// forces, drift. Stores and returns the new momentum; a non-finite position, velocity or momentum
// lowers `bad` to b.
[[gnu::always_inline]] inline Vec3 kick_drift(
    std::size_t b, bool kick, double hk, double h, double dt, Vec3* __restrict pos,
    Vec3* __restrict vel, Vec3* __restrict mom, const Vec3* __restrict force,
    const Vec3* __restrict torque, const double* __restrict inv_mass, std::int64_t& bad) {
  Vec3 v_full = vel[b], L_full = mom[b];
  if (kick) {
    v_full = v_full + (hk * inv_mass[b]) * force[b];
    L_full = L_full + hk * torque[b];
  }
  const Vec3 v = v_full + (h * inv_mass[b]) * force[b];
  const Vec3 L = L_full + h * torque[b];
  const Vec3 p = pos[b] + dt * v;
  if (!std::isfinite(p.sum() + v.sum() + L.sum())) bad = std::min(bad, static_cast<std::int64_t>(b));
  vel[b] = v;
  mom[b] = L;
  pos[b] = p;
  return L;
}

// kick_drift(), then the rotation over the step.
[[gnu::always_inline]] inline void kick_drift_rotate(
    std::size_t b, bool iso, bool kick, double hk, double h, double dt, Vec3* __restrict pos,
    Quat* __restrict rot, Vec3* __restrict vel, Vec3* __restrict mom, const Vec3* __restrict force,
    const Vec3* __restrict torque, const double* __restrict inv_mass,
    const Vec3* __restrict inv_inertia, std::int64_t& bad) {
  const Vec3 L = kick_drift(b, kick, hk, h, dt, pos, vel, mom, force, torque, inv_mass, bad);
  Quat q = rot[b];
  free_rotation_step(q, L, inv_inertia[b], iso, dt);
  rot[b] = q;
}

// The contact kernel's record of a body (sim/contact_view.hpp): half-step velocities and, for the
// dashpots, v~ = v + h F / m with the given predicted angular velocity w~; the centre of mass.
inline void fill_body_view(BodyView& bv, const Vec3& v, const Vec3& w, const Vec3& w_end,
                           const Vec3& force, double inv_mass, double h, const Vec3& position) {
  bv.velocity_m_s = v;
  bv.angular_velocity = w;
  bv.velocity_end_m_s = v + (h * inv_mass) * force;
  bv.angular_velocity_end = w_end;
  bv.inv_mass = inv_mass;
  bv.position_m = position;
}

// The contact kernel's record of a sphere.
inline void fill_sphere_view(SphereView& sv, const Vec3& centre, double radius) {
  sv.position_m = centre;
  sv.radius_m = radius;
}

// A lone sphere at its body's centre of mass: kick_drift(), views and skin check as for any body,
// the same operations in the same order, without the orientation (which moves no sphere of it) and
// the offset: 64 bytes a body and step fewer to stream through a bed larger than the cache, with
// the same bits (docs/results/solver_speed.md).
[[gnu::always_inline]] inline void lone_sphere_step(
    std::size_t b, bool kick, double hk, double h, double hp, double dt, Vec3* __restrict pos,
    Vec3* __restrict vel, Vec3* __restrict mom, Vec3* __restrict omega,
    const Vec3* __restrict force, const Vec3* __restrict torque,
    const double* __restrict inv_mass, const Vec3* __restrict inv_inertia, std::uint32_t i,
    const double* __restrict radius, Vec3* __restrict centre, BodyView* __restrict bview, SphereView* __restrict sview,
    const Vec3* __restrict ref, double& max_moved_sq, std::int64_t& bad) {
  const Vec3 L = kick_drift(b, kick, hk, h, dt, pos, vel, mom, force, torque, inv_mass, bad);
  const Vec3 v = vel[b], p = pos[b], T = torque[b];
  const double ii = inv_inertia[b].x();
  const Vec3 w = L * ii;
  omega[b] = w;
  fill_body_view(bview[b], v, w, Vec3(L + hp * T) * ii, force[b], inv_mass[b], hp, p);
  centre[i] = p;
  fill_sphere_view(sview[i], p, radius[i]);
  if (ref) max_moved_sq = std::max(max_moved_sq, (p - ref[i]).squaredNorm());
}

}  // namespace

void Simulation::update_sphere_positions() {
  const std::size_t n = spheres_.size();
#pragma omp parallel for schedule(static) num_threads(options_.threads) if (options_.threads > 1)
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t b = spheres_.body[i];
    spheres_.position_m[i] = sphere_centre(
        bodies_.position_m[b], sphere_rotation(bodies_.orientation[b]), spheres_.offset_body_m[i]);
  }
}

void Simulation::refresh_views(double h) {
  const std::size_t nb = bodies_.size(), ns = spheres_.size();
  body_view_.resize(nb);
  sphere_view_.resize(ns);
#pragma omp parallel for schedule(static) num_threads(options_.threads) if (options_.threads > 1)
  for (std::size_t b = 0; b < nb; ++b) {
    const Vec3 w_end =
        h == 0.0 ? bodies_.angular_velocity[b]
                 : angular_velocity_from_momentum(
                       bodies_.orientation[b], bodies_.inv_inertia[b],
                       Vec3(bodies_.angular_momentum[b] + h * bodies_.torque_n_m[b]),
                       bodies_.isotropic[b] != 0);
    fill_body_view(body_view_[b], bodies_.velocity_m_s[b], bodies_.angular_velocity[b], w_end,
                   bodies_.force_n[b], bodies_.inv_mass[b], h, bodies_.position_m[b]);
    for (std::uint32_t i = bodies_.first_sphere[b]; i < bodies_.first_sphere[b + 1]; ++i)
      fill_sphere_view(sphere_view_[i], spheres_.position_m[i], spheres_.radius_m[i]);
  }
}

void Simulation::size_thread_buffers() {
  const auto t = static_cast<std::size_t>(options_.threads);
  const std::size_t nb = bodies_.size(), nw = walls_.size();
  // The accumulators are zero between steps: the force reduction clears what it reads
  // (compute_forces), so new ones start at zero too.
  BodyAccumulator zero;
  zero.force_n.setZero();
  zero.torque_n_m.setZero();
  zero.roll_capacity_n_m = 0.0;
  thread_body_acc_.resize(t);
  for (auto& acc : thread_body_acc_)
    if (acc.size() < nb) acc.resize(nb, zero);
  thread_body_touched_.resize(t);
  for (auto& touched : thread_body_touched_)
    if (touched.size() < nb) touched.resize(nb, 0);
  thread_wall_acc_.assign(t, std::vector<WallAccumulator>(nw));
  thread_acc_ptr_.resize(t);
  thread_touched_ptr_.resize(t);
  for (std::size_t k = 0; k < t; ++k) {
    thread_acc_ptr_[k] = thread_body_acc_[k].data();
    thread_touched_ptr_[k] = thread_body_touched_[k].data();
  }
  thread_cdt_wall_.resize(t);
  thread_scratch_.resize(t);
}

void Simulation::ensure_ready() {
  if (ready_) return;
  settle();
  double r_max = 0.0;
  for (double r : spheres_.radius_m) r_max = std::max(r_max, r);
  skin_m_ = options_.skin_m > 0.0 ? options_.skin_m : 0.2 * r_max;
  size_thread_buffers();
  update_sphere_positions();
  rebuild_lists();
  ready_ = true;
  compute_forces(false);
  if (reference_energy_j_ < 0.0) {
    reference_energy_j_ = energy_budget_j();
    reference_potential_j_ = potential_energy_j();
  }
}

void Simulation::rebuild_lists() {
  // Rolling-spring history exists only for EPSD: no rolling history when it is not needed.
  const bool rolling_history = options_.contact.rolling == RollingModel::epsd;
  pairs_.build(spheres_, skin_m_, rolling_history, options_.threads);
  wall_pairs_.build(spheres_, walls_, skin_m_, rolling_history);
  wall_pose_at_build_.clear();
  for (const Wall& w : walls_) wall_pose_at_build_.push_back(w.pose);
  ++lists_version_;
}

// Spheres and walls each may use half the skin before a pair can be missed; a wall's share is
// bounded by how far its surface moved since the last build.
bool Simulation::walls_moved_beyond_skin() const {
  for (std::size_t w = 0; w < walls_.size(); ++w) {
    if (!walls_[w].motion) continue;
    if (surface_displacement_m(*walls_[w].shape, wall_pose_at_build_[w], walls_[w].pose) >
        0.5 * skin_m_)
      return true;
  }
  return false;
}

void Simulation::finish_kick() {
  if (!kick_pending_) return;
  const std::size_t nb = bodies_.size();
  const double hk = 0.5 * kick_dt_s_;
#pragma omp parallel for schedule(static) num_threads(options_.threads) if (options_.threads > 1)
  for (std::size_t b = 0; b < nb; ++b) {
    const Vec3 L = bodies_.angular_momentum[b] + hk * bodies_.torque_n_m[b];
    bodies_.velocity_m_s[b] += (hk * bodies_.inv_mass[b]) * bodies_.force_n[b];
    bodies_.angular_momentum[b] = L;
    bodies_.angular_velocity[b] = angular_velocity_from_momentum(
        bodies_.orientation[b], bodies_.inv_inertia[b], L, bodies_.isotropic[b] != 0);
  }
  kick_pending_ = false;
}

void Simulation::move_bodies(std::size_t b_begin, std::size_t b_end, double dt, bool kick,
                             double hk, const Vec3* ref, double& max_moved_sq,
                             std::int64_t& bad) {
  // Dashpot velocities (contact/hertz_mindlin.hpp): the half-step ones (hp = 0), or with
  // ContactOptions::dashpot_predicted v~_{n+1} = v_{n+1/2} + dt/2 F_n / m and
  // L~_{n+1} = L_{n+1/2} + dt/2 T_n (Groot & Warren 1997, eq. 17 with lambda = 1), with F_n, T_n
  // the forces of the previous step still held by the bodies.
  const double h = 0.5 * dt;
  const double hp = options_.contact.dashpot_predicted ? h : 0.0;
  // Raw pointers: the stores to the views must not make the compiler reload the state.
  Vec3* __restrict pos = bodies_.position_m.data();
  Quat* __restrict rot = bodies_.orientation.data();
  Vec3* __restrict vel = bodies_.velocity_m_s.data();
  Vec3* __restrict mom = bodies_.angular_momentum.data();
  Vec3* __restrict omega = bodies_.angular_velocity.data();
  const Vec3* __restrict force = bodies_.force_n.data();
  const Vec3* __restrict torque = bodies_.torque_n_m.data();
  const double* __restrict inv_mass = bodies_.inv_mass.data();
  const Vec3* __restrict inv_inertia = bodies_.inv_inertia.data();
  const std::uint8_t* __restrict iso_flag = bodies_.isotropic.data();
  const std::uint32_t* __restrict first = bodies_.first_sphere.data();
  const Vec3* __restrict offset = spheres_.offset_body_m.data();
  const double* __restrict radius = spheres_.radius_m.data();
  Vec3* __restrict centre = spheres_.position_m.data();
  BodyView* __restrict bview = body_view_.data();
  SphereView* __restrict sview = sphere_view_.data();
  // Blocks of bodies, each in two passes: the kick, drift and rotation of the block's clumps,
  // then the views and spheres of all its bodies (a sphere's kick, drift and rotation there). A
  // clump's rotation is a chain of dependent operations (integrate/free_rotation.hpp); in a short
  // first loop the processor overlaps the chains of several clumps, which one loop doing each
  // body's rotation and spheres together would not let it do (docs/results/solver_speed.md). A
  // block stays in the first-level cache between the passes; spheres stay in one pass, where a
  // second costs more than it saves.
  constexpr std::size_t kBlock = 32;
  for (std::size_t b_block = b_begin; b_block < b_end; b_block += kBlock) {
    const std::size_t block_end = std::min(b_end, b_block + kBlock);
    for (std::size_t b = b_block; b < block_end; ++b)
      if (iso_flag[b] == 0)
        kick_drift_rotate(b, false, kick, hk, h, dt, pos, rot, vel, mom, force, torque, inv_mass,
                          inv_inertia, bad);
    for (std::size_t b = b_block; b < block_end; ++b) {
      if (iso_flag[b] == 2) {
        lone_sphere_step(b, kick, hk, h, hp, dt, pos, vel, mom, omega, force, torque, inv_mass,
                         inv_inertia, first[b], radius, centre, bview, sview, ref,
                         max_moved_sq, bad);
        continue;
      }
      const bool iso = iso_flag[b] != 0;
      if (iso)  // a short rotation: no chain to overlap
        kick_drift_rotate(b, true, kick, hk, h, dt, pos, rot, vel, mom, force, torque, inv_mass,
                          inv_inertia, bad);
      const Vec3 v = vel[b], L = mom[b], p = pos[b];
      const Quat q = rot[b];
      const Vec3 w = angular_velocity_from_momentum(q, inv_inertia[b], L, iso);
      omega[b] = w;
      fill_body_view(bview[b], v, w,
                     angular_velocity_from_momentum(q, inv_inertia[b], Vec3(L + hp * torque[b]), iso),
                     force[b], inv_mass[b], hp, p);
      // The rotation matrix only when some sphere is off the centre of mass (not for a lone
      // sphere).
      Mat3 rotation;
      bool rotated = false;
      for (std::uint32_t i = first[b]; i < first[b + 1]; ++i) {
        if (!rotated && !offset[i].isZero(0.0)) {
          rotation = sphere_rotation(q);
          rotated = true;
        }
        const Vec3 c = rotated ? sphere_centre(p, rotation, offset[i]) : p;
        centre[i] = c;
        fill_sphere_view(sview[i], c, radius[i]);
        if (ref) max_moved_sq = std::max(max_moved_sq, (c - ref[i]).squaredNorm());
      }
    }
  }
}

void Simulation::update_work_shares() {
  if (shares_version_ == lists_version_) return;
  const auto nt = static_cast<std::size_t>(std::max(1, options_.threads));
  const std::size_t nb = bodies_.size();
  const std::uint32_t* body_of_sphere = spheres_.body.data();
  const auto& gs = pairs_.group_start();
  const auto& si = pairs_.si();
  const auto& wgs = wall_pairs_.group_start();
  const auto& ws = wall_pairs_.sphere();
  work_shares_ = split_contact_work(
      {gs, pairs_.group_count(), [&](std::size_t g) { return body_of_sphere[si[gs[g]]]; }},
      {wgs, wall_pairs_.group_count(), [&](std::size_t g) { return body_of_sphere[ws[wgs[g]]]; }},
      nb, nt);
  split_bodies_by_spheres(bodies_.first_sphere, nb, work_shares_);
  shares_version_ = lists_version_;
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
  const std::vector<WorkShare>& shares = work_shares_;
  const bool sort_due = options_.sort_interval_steps > 0 &&
                        (step_ + 1) % options_.sort_interval_steps == 0 && nb >= 512;
  // The previous step's second half kick, when pending, with that step's dt (finish_kick()).
  const bool kick = kick_pending_;
  const double hk = 0.5 * kick_dt_s_;
  kick_pending_ = false;
  body_view_.resize(nb);
  sphere_view_.resize(ns);
  // Skin check against the centres at the last neighbour build (none after a renumbering).
  const std::vector<Vec3>& built = pairs_.built_at();
  const Vec3* ref = built.size() == ns ? built.data() : nullptr;
  // Valid for this step's forces unless the lists are rebuilt (then compute_forces() sets them up
  // again).
  prepare_forces();
  step_moved_sq_.assign(static_cast<std::size_t>(nt), 0.0);
  step_bad_.assign(static_cast<std::size_t>(nt), std::numeric_limits<std::int64_t>::max());
  bool walls_moved = false, rebuild = false;
  std::int64_t force_bad = std::numeric_limits<std::int64_t>::max();
#pragma omp parallel num_threads(nt) if (nt > 1) reduction(min : force_bad)
  {
    const int t = omp_get_thread_num(), team = omp_get_num_threads();
    double moved_sq = 0.0;
    std::int64_t bad = std::numeric_limits<std::int64_t>::max();
    for (std::size_t sh = static_cast<std::size_t>(t); sh < shares.size();
         sh += static_cast<std::size_t>(team))
      move_bodies(shares[sh].move_begin, shares[sh].move_end, dt, kick, hk, ref, moved_sq, bad);
    step_moved_sq_[static_cast<std::size_t>(t)] = moved_sq;
    step_bad_[static_cast<std::size_t>(t)] = bad;
    if (t == 0) {
      for (Wall& w : walls_)
        if (w.motion) w.motion->advance(w, time_s_, dt);
      time_s_ += dt;
      ++step_;
      walls_moved = walls_moved_beyond_skin();
    }
#pragma omp barrier
    // Every thread reaches the same decision from the same values.
    double moved_all_sq = 0.0;
    for (double m : step_moved_sq_) moved_all_sq = std::max(moved_all_sq, m);
    const bool rebuild_now = ref == nullptr || moved_all_sq > pairs_.rebuild_distance_sq();
    if (t == 0) {
      rebuild = rebuild_now;
      lap(prof, t0, profile_.integrate_s);
    }
    if (!rebuild_now && !walls_moved && !sort_due) forces_in_region(t, team, dt, t0, force_bad);
  }
  std::int64_t first_bad = -1;
  if (rebuild || walls_moved || sort_due) {
    if (sort_due && sort_spatially()) {
      refresh_views(options_.contact.dashpot_predicted ? 0.5 * dt : 0.0);
      rebuild = false;  // the renumbering rebuilt the lists
    }
    if (rebuild || walls_moved_beyond_skin()) rebuild_lists();
    lap(prof, t0, profile_.neighbour_s);
    // Forces at t_{n+1}; their second half kick is left pending (finish_kick()).
    first_bad = compute_forces(true);
  } else {
    first_bad = finish_forces(true, force_bad);
    lap(prof, t0, profile_.reduce_s);
  }
  std::int64_t moved_bad = std::numeric_limits<std::int64_t>::max();
  for (std::int64_t b : step_bad_) moved_bad = std::min(moved_bad, b);
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

// Energy the scene can supply beyond its potential energy: the kinetic energy at the start, the
// kinetic energy every body would have at the fastest moving wall's speed, and a floor of each body
// falling one largest-sphere diameter (so a resting bed has a non-zero budget). The guard compares
// this with the kinetic energy plus the potential energy released since the start, which damped
// contacts can only lower.
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
    if (ke - released > limit) {
      std::size_t worst = 0;
      double worst_e = -1.0;
      for (std::size_t b = 0; b < nb; ++b) {
        const double e = bodies_.mass_kg[b] * bodies_.velocity_m_s[b].squaredNorm();
        if (e > worst_e) { worst_e = e; worst = b; }
      }
      std::ostringstream m;
      m << "kinetic energy " << ke << " J, less the potential energy released (" << released
        << " J), exceeds " << options_.guards.max_energy_factor
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
