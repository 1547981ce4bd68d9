// The forces of a step: the contact pass (sim/contact_forces.cpp) and the reduction of the
// threads' accumulators to each body's force and torque, with CDT's rolling torque and the NaN
// guard; then the walls' totals, the step's statistics and the overlap guard.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

#include <omp.h>

#include "solver/contact/rolling_cdt_torque.hpp"
#include "solver/sim/contact_forces.hpp"
#include "solver/sim/phase_clock.hpp"
#include "solver/sim/simulation.hpp"

namespace seedcal {

std::int64_t Simulation::compute_forces(bool mid_step) {
  const bool prof = options_.profile;
  auto t0 = prof ? std::chrono::steady_clock::now() : std::chrono::steady_clock::time_point{};
  // Inside step() the views were refreshed by the body pass (or after a spatial sort).
  if (!mid_step) contacts_.refresh_views(bodies_, spheres_, 0.0, options_.threads);
  prepare_forces();
  // The torques computed now act over the second half of this step and the first half of the
  // next (velocity Verlet): over dt from mid-step, over dt/2 when the velocities are at the force
  // time (the first call).
  const double h = mid_step ? options_.dt_s : 0.5 * options_.dt_s;
  const int nt = std::max(1, options_.threads);
  std::int64_t first_bad = std::numeric_limits<std::int64_t>::max();
#pragma omp parallel num_threads(nt) if (nt > 1) reduction(min : first_bad)
  {
    forces_in_region(omp_get_thread_num(), omp_get_num_threads(), h, t0, first_bad);
  }
  first_bad = finish_forces(mid_step, first_bad);
  lap(prof, t0, profile_.reduce_s);
  return first_bad;
}

void Simulation::prepare_forces() {
  update_work_shares();
  prepare_contact_pass(contact_inputs(), contacts_);
  if (options_.contact.rolling == RollingModel::cdt) cdt_torque_per_capacity_.resize(bodies_.size());
}

void Simulation::forces_in_region(int thread, int team, double h,
                                  std::chrono::steady_clock::time_point& t0,
                                  std::int64_t& first_bad) {
  run_contact_pass(contact_inputs(), contacts_, threads_, thread, team);
#pragma omp barrier
  if (thread == 0) lap(options_.profile, t0, profile_.contact_s);
  reduce_forces(thread, team, h, first_bad);
}

void Simulation::reduce_forces(int thread, int team, double h, std::int64_t& first_bad) {
  const std::size_t nt = threads_.body_acc.size();
  const Vec3 g = options_.gravity_m_s2;
  const bool cdt = options_.contact.rolling == RollingModel::cdt;
  const bool cdt_limit = options_.contact.cdt_stop_limit;
  // Raw pointers, so that the stores do not make the compiler reload the state.
  BodyAccumulator* const* __restrict acc_ptr = threads_.acc_ptr.data();
  std::uint8_t* const* __restrict touched_ptr = threads_.touched_ptr.data();
  const double* __restrict mass = bodies_.mass_kg.data();
  const Vec3* __restrict mom = bodies_.angular_momentum.data();
  const Vec3* __restrict omega = bodies_.angular_velocity.data();
  Vec3* __restrict force = bodies_.force_n.data();
  Vec3* __restrict torque = bodies_.torque_n_m.data();
  Vec3* __restrict cdt_u = cdt ? cdt_torque_per_capacity_.data() : nullptr;
  // Sum the threads' shares in thread order and settle the CDT torque; the NaN guard rides along
  // (lowest bad body reported). The bodies are those whose contacts this thread computed
  // (sim/work_split.hpp): the same sums in the same order whichever thread adds them. Blocks of
  // bodies in two passes, as in the body pass (integrate/velocity_verlet.cpp): the sums, then the
  // CDT torques, whose square root and division form a chain per body that a short second loop
  // lets the processor overlap across bodies.
  constexpr std::size_t kBlock = 32;
  double capacity[kBlock];
  for (std::size_t sh = static_cast<std::size_t>(thread); sh < threads_.shares.size();
       sh += static_cast<std::size_t>(team))
  for (std::size_t b_block = threads_.shares[sh].body_begin; b_block < threads_.shares[sh].body_end;
       b_block += kBlock) {
    const std::size_t block_end = std::min(threads_.shares[sh].body_end, b_block + kBlock);
    for (std::size_t b = b_block; b < block_end; ++b) {
      Vec3 f = mass[b] * g, tq = Vec3::Zero();
      double c = 0.0;
      for (std::size_t t = 0; t < nt; ++t) {
        // A thread's accumulator is read only where it wrote this step (the others hold zero).
        if (!touched_ptr[t][b]) continue;
        touched_ptr[t][b] = 0;
        BodyAccumulator& acc = acc_ptr[t][b];
        f += acc.force_n;
        tq += acc.torque_n_m;
        if (cdt) c += acc.roll_capacity_n_m;
        // Cleared for the next step here, where the line is in cache and the bodies are split
        // between the threads, instead of by every thread over every body in the kernel.
        acc.force_n.setZero();
        acc.torque_n_m.setZero();
        acc.roll_capacity_n_m = 0.0;
      }
      force[b] = f;
      torque[b] = tq;
      capacity[b - b_block] = c;
    }
    if (cdt) {
      for (std::size_t b = b_block; b < block_end; ++b) {
        const double c = capacity[b - b_block];
        Vec3 u = Vec3::Zero();
        if (c > 0.0) u = cdt_limit ? cdt_stop_limited(mom[b], torque[b], c, h) : cdt_sign_direction(omega[b]);
        cdt_u[b] = u;
        torque[b] += c * u;
      }
    }
    for (std::size_t b = b_block; b < block_end; ++b)
      if (!std::isfinite(force[b].sum() + torque[b].sum())) {
        first_bad = std::min(first_bad, static_cast<std::int64_t>(b));
        break;
      }
  }
  // The walls take the reaction of their contacts' rolling torques (a drum feels it about its
  // axis): this thread's wall contacts are those of the bodies just summed, whose CDT directions
  // are now known, so no other thread need be waited for.
  if (cdt) {
    const auto t = static_cast<std::size_t>(thread);
    WallAccumulator* wall_acc = threads_.wall_acc[t].data();
    for (const CdtWallShare& share : threads_.cdt_wall[t])
      wall_acc[share.wall].torque_n_m -= share.capacity_n_m * cdt_u[share.body];
  }
}

std::int64_t Simulation::finish_forces(bool mid_step, std::int64_t first_bad) {
  const ThreadStats total = finish_contact_pass(contacts_.pass);
  const std::size_t nb = bodies_.size();
  const std::size_t nt = threads_.body_acc.size();
  const double dt = options_.dt_s;
  if (mid_step) {
    kick_pending_ = true;
    kick_dt_s_ = dt;
  }
  for (std::size_t w = 0; w < walls_.size(); ++w) {
    Vec3 f = Vec3::Zero(), tq = Vec3::Zero();
    double k = 0.0;
    int c = 0;
    for (std::size_t t = 0; t < nt; ++t) {
      const WallAccumulator& acc = threads_.wall_acc[t][w];
      f += acc.force_n;
      tq += acc.torque_n_m;
      k += acc.contact_stiffness_n_m;
      c += acc.contacts;
    }
    // The wall's work on the particles over this step (wall_work_j()): the trapezoidal rule on the
    // forces at the step's two ends, with the wall's velocity over the step.
    if (mid_step && walls_[w].motion)
      wall_work_j_ -= 0.5 * dt *
                      ((walls_[w].force_n + f).dot(walls_[w].pose.velocity_m_s) +
                       (walls_[w].torque_n_m + tq).dot(walls_[w].pose.angular_velocity_rad_s));
    walls_[w].force_n = f;
    walls_[w].torque_n_m = tq;
    walls_[w].contact_stiffness_n_m = k;
    walls_[w].contacts = c;
  }
  stats_ = StepStats{};
  stats_.sphere_contacts = total.sphere_contacts;
  stats_.wall_contacts = total.wall_contacts;
  stats_.max_overlap_m = total.max_overlap;
  stats_.max_normal_force_n = total.max_fn;
  if (options_.track_body_contacts) {
    contacts_.count_body_contacts(spheres_, nb, body_contacts_);
    for (int c : body_contacts_) stats_.max_body_contacts = std::max(stats_.max_body_contacts, c);
  }
  const DeepOverlap& deep = total.deep;
  deepest_overlap_fraction_ = std::max(deepest_overlap_fraction_, deep.deepest_fraction);
  if (deep.worst_ratio > 1.0 && failure_.status == RunStatus::ok) {
    std::ostringstream m;
    m << "overlap reached " << deep.worst_overlap_m << " m, " << deep.worst_overlap_m / deep.worst_radius_m
      << " of the radius of a sphere with r = " << deep.worst_radius_m << " m (limit "
      << deep.worst_limit_m << " m: " << options_.guards.max_overlap_fraction
      << " of a lone sphere's radius or of a clump's volume-equivalent radius, at most "
      << options_.guards.max_clump_sphere_overlap_fraction
      << " of a clump sphere's own; Hertz contact assumes an overlap much smaller than the radius)";
    // A clump whose spheres differ much in size: a small sphere standing out of a large one
    // takes the body's whole momentum alone before the large sphere touches.
    double r_body_max = 0.0;
    if (deep.worst_body >= 0) {
      const auto b = static_cast<std::size_t>(deep.worst_body);
      for (std::uint32_t i = bodies_.first_sphere[b]; i < bodies_.first_sphere[b + 1]; ++i)
        r_body_max = std::max(r_body_max, spheres_.radius_m[i]);
    }
    const std::string step_note = step_size_note();
    if (!step_note.empty()) {
      m << "; likely cause: " << step_note;
    } else if (r_body_max >= 5.0 * deep.worst_radius_m) {
      m << "; likely cause: the body's spheres range from r = " << deep.worst_radius_m << " to "
        << r_body_max << " m (radius ratio 1:" << r_body_max / deep.worst_radius_m
        << ") and the small sphere carries the body alone: make the small spheres of the clump "
           "larger or let them stand out less, or raise youngs_modulus_pa";
    } else {
      m << "; likely cause: particles too soft for the load (raise youngs_modulus_pa) or a time "
           "step too large for the impact speed (lower dt_s)";
    }
    fail(RunStatus::deep_overlap, deep.worst_body, m.str());
  }
  return first_bad == std::numeric_limits<std::int64_t>::max() ? -1 : first_bad;
}

}  // namespace seedcal
