#pragma once
// A Simulation is a value that owns its whole state: bodies, spheres, walls, neighbour lists and
// contact history, options, random generator and log sink. No global state, so many simulations
// can run in one process (DESIGN.md, STYLE.md).
#include <chrono>
#include <cstdint>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "solver/broadphase/verlet_list.hpp"
#include "solver/contact/contact_model.hpp"
#include "solver/core/body_state.hpp"
#include "solver/core/materials.hpp"
#include "solver/sim/body_def.hpp"
#include "solver/sim/contact_forces.hpp"
#include "solver/sim/contact_view.hpp"
#include "solver/sim/guards.hpp"
#include "solver/sim/kernel_scratch.hpp"
#include "solver/sim/work_split.hpp"
#include "solver/walls/wall.hpp"
#include "solver/walls/wall_contact_list.hpp"

namespace seedcal {

class Simulation;

// Frames of a run for output (a trajectory): on_frame(sim) is called at the first step (t = 0),
// at the start of the first step at or after each multiple of interval_s, when a guard stops the
// run (the state that stopped it) and from final_check() (the state the scene ends with), never
// twice for the same step. It sees the simulation read-only, so the run is the same with or
// without it; unset (no on_frame), it costs one comparison per step. One simulation per observer:
// a scene that runs several passes the observer to the one it measures.
//
// Progress (optional, for a status line, never for output): on_progress(sim) at the start of the
// first step at or after each multiple of progress_interval_s of simulated time; read-only too.
struct FrameObserver {
  double interval_s = 0.0;  // > 0 when on_frame is set
  std::function<void(const Simulation&)> on_frame;
  double progress_interval_s = 0.0;  // > 0 when on_progress is set
  std::function<void(const Simulation&)> on_progress;
};

struct SimulationOptions {
  ContactOptions contact;
  Vec3 gravity_m_s2 = Vec3(0.0, 0.0, -9.81);
  double dt_s = 0.0;    // must be set (see sim/time_step.hpp and choose_time_step())
  double skin_m = 0.0;  // Verlet skin; 0: 10 % of the largest sphere diameter
  int threads = 1;      // OpenMP threads inside this simulation
  GuardOptions guards;
  bool track_body_contacts = false;  // count sphere-level contacts per body each step
  bool profile = false;              // accumulate wall time per phase of the step (StepProfile)
  // Re-sort bodies (and their spheres) along a space-filling curve every this many steps, so
  // neighbours are near in memory (0: never), within one slab of the bed per thread (the order,
  // and so the bits, depend on `threads`). Worlds under 512 bodies are never sorted.
  std::uint64_t sort_interval_steps = 1000;
  std::uint64_t seed = 0;
  // Compute sphere-sphere and sphere-wall contacts this many at a time at most: 8 (AVX-512F), 4
  // (AVX2) or 1, the widest the CPU runs (sim/pair_batch.hpp); the results are the same bits at
  // any width.
  int simd_lanes = 8;
  FrameObserver observer;
};

// Per-step contact statistics (always collected; maxima are order-independent).
struct StepStats {
  std::size_t sphere_contacts = 0;  // touching sphere-sphere pairs
  std::size_t wall_contacts = 0;    // touching sphere-wall pairs
  double max_overlap_m = 0.0;
  double max_normal_force_n = 0.0;
  int max_body_contacts = 0;        // with track_body_contacts: most sphere contacts of one body
};

// Wall seconds spent in each phase of step(), accumulated when SimulationOptions::profile is on.
struct StepProfile {
  double integrate_s = 0.0;   // first half kick, drift, rotation, sphere positions, contact
                              // views, skin check, wall motion
  double neighbour_s = 0.0;   // spatial sort and neighbour-list rebuilds
  double contact_s = 0.0;     // contact force kernel
  double reduce_s = 0.0;      // per-thread force reduction, CDT torque, second half kick, guards
};

class Simulation {
 public:
  Simulation(InteractionTable table, SimulationOptions options);

  // Building the world. Bodies get consecutive ids in the order they are added. Their storage
  // index may change when the world is re-sorted in space: find a body with index_of(id).
  // Both throw std::invalid_argument when the new body's or wall's material has no interaction
  // with a material it can touch (any body's, or a wall's for a body): such a pair would pass
  // through each other with zero force.
  std::uint32_t add_body(const BodyDef& def);
  std::size_t add_wall(Wall wall);
  void set_log(std::function<void(const std::string&)> sink) { log_ = std::move(sink); }

  // Advances one step. Returns false (and fills failure()) when a guard stops the run.
  bool step();
  // Advances up to n steps; stops early on a guard failure.
  bool run(std::uint64_t n);
  // Runs every guard now, the energy guard included (inside step() it runs only every
  // GuardOptions::check_interval steps, so a run shorter than that, or one that blows up after its
  // last check, would end unchecked). Scenes call it when they end; it also takes the last frame
  // (FrameObserver). Returns false on a failure.
  bool final_check();

  std::uint32_t index_of(std::uint32_t id) const { return index_of_id_[id]; }
  // The bodies at the end of the last step (see finish_kick()).
  const BodyState& bodies() const {
    settle();
    return bodies_;
  }
  BodyState& bodies() {
    settle();
    return bodies_;
  }
  const SphereState& spheres() const { return spheres_; }
  const std::vector<Wall>& walls() const { return walls_; }
  std::vector<Wall>& walls() { return walls_; }
  const InteractionTable& table() const { return table_; }
  const SimulationOptions& options() const { return options_; }
  const StepStats& stats() const { return stats_; }
  const std::vector<int>& body_contacts() const { return body_contacts_; }
  const GuardFailure& failure() const { return failure_; }
  const StepProfile& profile() const { return profile_; }
  double time_s() const { return time_s_; }
  std::uint64_t step_count() const { return step_; }
  std::size_t neighbour_builds() const { return pairs_.builds(); }
  std::size_t neighbour_pairs() const { return pairs_.pair_count(); }
  std::mt19937_64& rng() { return rng_; }

  double kinetic_energy_j() const;
  double potential_energy_j() const;
  // Smallest Rayleigh time step over all spheres (sim/time_step.hpp), s.
  double rayleigh_time_step_s() const;
  // Removes the bodies for which `remove(storage index)` is true (e.g. struck off above a rim);
  // the others keep their ids and their contact history.
  void remove_bodies(const std::function<bool(std::uint32_t index)>& remove);
  // Changes the time step between steps (velocity Verlet carries the last forces over).
  void set_time_step(double dt_s);
  // Sets a body's velocity and angular velocity (world frame).
  void set_body_motion(std::uint32_t b, const Vec3& v, const Vec3& w);

 private:
  friend struct ForceKernel;
  void update_sphere_positions();
  void ensure_ready();
  // The body pass of step() over bodies [b_begin, b_end) (one thread's range): the first half of
  // a velocity Verlet step (kick, drift, rotation) after the previous step's pending second half
  // kick (`kick`, over hk; finish_kick()), fused with placing the spheres and refreshing the
  // contact views. Sets max_moved_sq to at least the largest squared displacement of their
  // spheres since `ref` (the centres at the last neighbour build; null: none) and `bad` to at most
  // the lowest body whose new state is not finite.
  void move_bodies(std::size_t b_begin, std::size_t b_end, double dt, bool kick, double hk,
                   const Vec3* ref, double& max_moved_sq, std::int64_t& bad);
  // Recomputes work_shares_ when the lists changed (a rebuild or a renumbering; adding or
  // removing bodies always ends in one).
  void update_work_shares();
  // The second half kick of velocity Verlet, v += dt/2 F / m and L += dt/2 T with the forces just
  // computed, is left pending at the end of step(): the next step's first half kick follows it in
  // the same pass over the bodies, which then reads and writes each body's state once instead of
  // twice. Anything that reads or changes the bodies between steps (the bodies() accessors, the
  // energies, set_body_motion, remove_bodies, adding bodies) applies it first, with the angular
  // velocity it implies; the arithmetic is the same either way, so results are the same bits.
  void finish_kick();
  void settle() const {
    // Only the pending kick changes: a Simulation is never itself a const object.
    if (kick_pending_) const_cast<Simulation*>(this)->finish_kick();
  }
  // `mid_step`: the bodies hold half-step velocities (inside step()), so the dashpots get the
  // predicted end-of-step velocities, and the second half kick is left pending (finish_kick());
  // false when the velocities are already at the force time (then nothing is kicked).
  // Returns the lowest body whose force or torque is not finite, or -1.
  std::int64_t compute_forces(bool mid_step);
  // The one-thread set-up of a step's forces: the threads' shares, the contact pass's arguments,
  // CDT's per-body buffer.
  void prepare_forces();
  // Inside a parallel region (or alone): thread `thread` of `team` computes the contacts of its
  // shares, waits for the others, and sums its bodies' forces (reduce_forces()); the master
  // thread takes the contact phase's lap.
  void forces_in_region(int thread, int team, double h,
                        std::chrono::steady_clock::time_point& t0, std::int64_t& first_bad);
  // Thread `thread` of a team of `team`, after the contact pass: the forces and torques of its
  // shares' bodies summed over the threads' accumulators (CDT torques over dt `h`), and its wall
  // contacts' rolling-torque reactions. Lowers first_bad to a body whose sum is not finite.
  void reduce_forces(int thread, int team, double h, std::int64_t& first_bad);
  // The serial end of the forces: wall totals, statistics, the overlap guard; the second half
  // kick left pending when `mid_step`. Returns first_bad, or -1 for none (max).
  std::int64_t finish_forces(bool mid_step, std::int64_t first_bad);
  // Rebuilds the contact views from the state (sim/contact_view.hpp), with dashpot velocities
  // predicted over h (0: the velocities are at the force time).
  void refresh_views(double h);
  // Grows the per-thread accumulators to the current body and wall counts.
  void size_thread_buffers();
  bool check_guards(bool energy_now = false);
  // Calls the frame observer with the current state (FrameObserver) and schedules the next frame.
  void emit_frame();
  double energy_budget_j() const;
  void rebuild_lists();
  // Returns true when the bodies were renumbered (the neighbour lists are then rebuilt).
  bool sort_spatially();
  std::vector<std::uint32_t> thread_slabs(const Vec3& lo, const Vec3& hi) const;
  void reorder_bodies(const std::vector<std::uint32_t>& old_of_new);
  bool walls_moved_beyond_skin() const;
  void fail(RunStatus s, std::int64_t body, std::string message);
  std::string step_size_note() const;
  // Throws std::invalid_argument naming the two materials when `material` (a new body's, or a new
  // wall's when `wall`) has no interaction with a material it can touch.
  void require_interactions(std::uint16_t material, bool wall, const std::string& what) const;

  InteractionTable table_;
  SimulationOptions options_;
  BodyState bodies_;
  SphereState spheres_;
  std::vector<Wall> walls_;
  // Materials present among the bodies and among the walls (indexed by material).
  std::vector<char> body_materials_, wall_materials_;
  VerletList pairs_;
  WallContactList wall_pairs_;
  StepStats stats_;
  std::vector<int> body_contacts_;
  std::vector<int> sphere_group_touch_, wall_group_touch_;
  // CDT (contact/rolling_cdt.hpp): per thread, the wall contacts' shares of the rolling-torque
  // capacity (the wall takes the reaction); per body, the torque per unit of capacity that
  // compute_forces() settles on.
  struct CdtWallShare {
    std::uint32_t wall, body;
    double capacity_n_m;
  };
  std::vector<std::vector<CdtWallShare>> thread_cdt_wall_;
  std::vector<KernelScratch> thread_scratch_;  // the contact kernel's buffers, one per thread
  std::vector<Vec3> cdt_torque_per_capacity_;
  // What the contact kernel reads (sim/contact_view.hpp): spheres and bodies, with the predicted
  // end-of-step velocities for the dashpots (contact/hertz_mindlin.hpp).
  std::vector<SphereView> sphere_view_;
  std::vector<BodyView> body_view_;
  // Per-thread force, torque and rolling-capacity accumulators (at least one per body), reduced
  // in thread order (deterministic for a given thread count).
  std::vector<std::vector<BodyAccumulator>> thread_body_acc_;
  // Per thread, 1 for a body whose accumulator the thread wrote this step: the reduction reads
  // only those (a thread's contacts reach few of the other threads' bodies) and clears them.
  std::vector<std::vector<std::uint8_t>> thread_body_touched_;
  std::vector<std::vector<WallAccumulator>> thread_wall_acc_;
  std::vector<BodyAccumulator*> thread_acc_ptr_;      // thread_body_acc_[t].data()
  std::vector<std::uint8_t*> thread_touched_ptr_;     // thread_body_touched_[t].data()
  ContactPass contact_pass_;                          // the contact kernel's set-up, per step
  // How a step's work is split between the threads (sim/work_split.hpp): recomputed when the
  // lists change (lists_version_ counts rebuilds and renumberings).
  std::vector<WorkShare> work_shares_;
  std::uint64_t lists_version_ = 0, shares_version_ = ~std::uint64_t{0};
  // Per thread, the body pass's largest squared sphere displacement and lowest bad body.
  std::vector<double> step_moved_sq_;
  std::vector<std::int64_t> step_bad_;
  std::vector<WallPose> wall_pose_at_build_;
  std::vector<std::uint32_t> index_of_id_;
  GuardFailure failure_;
  StepProfile profile_;
  std::function<void(const std::string&)> log_;
  std::mt19937_64 rng_;
  double time_s_ = 0.0;
  std::uint64_t step_ = 0;
  // Time of the next frame (+inf without an observer) and the step of the last frame taken.
  double next_frame_s_ = std::numeric_limits<double>::infinity();
  double next_progress_s_ = std::numeric_limits<double>::infinity();
  std::uint64_t last_frame_step_ = std::numeric_limits<std::uint64_t>::max();  // none yet
  double skin_m_ = 0.0;
  double reference_energy_j_ = -1.0;  // < 0: recompute
  double reference_potential_j_ = 0.0;
  bool ready_ = false;
  bool kick_pending_ = false;  // finish_kick() not yet applied
  double kick_dt_s_ = 0.0;     // the step it belongs to
};

}  // namespace seedcal
