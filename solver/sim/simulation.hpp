#pragma once
// A Simulation is a value that owns its whole state: bodies, spheres, walls, neighbour lists and
// contact history, options, random generator and log sink. No global state, so many simulations
// can run in one process (DESIGN.md, STYLE.md). It coordinates its parts, each in a file of its
// own: the state of the bodies and spheres (core/body_state.hpp) and of the walls
// (walls/wall.hpp); the integrator (integrate/velocity_verlet.hpp, integrate/free_rotation.hpp);
// the contact pipeline (sim/contact_pipeline.hpp: lists, history, views, the kernel's set-up; the
// law in contact/contact_law.hpp); the thread plan (sim/thread_plan.hpp: work shares and the
// threads' buffers; the spatial sort in sim/spatial_sort.cpp); the options and their checks
// (sim/simulation_options.hpp); the guards (sim/guards.hpp).
#include <chrono>
#include <cstdint>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "solver/core/body_state.hpp"
#include "solver/core/materials.hpp"
#include "solver/sim/body_def.hpp"
#include "solver/sim/contact_pipeline.hpp"
#include "solver/sim/guards.hpp"
#include "solver/sim/simulation_options.hpp"
#include "solver/sim/thread_plan.hpp"
#include "solver/walls/wall.hpp"

namespace seedcal {

class Simulation;

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
  // The deepest overlap of the run so far over the smaller radius of its pair (or the sphere's,
  // at a wall), where it passed the guard's prefilter (overlap_prefilter_fraction, half the radius
  // by default); 0 when no contact went that deep. Between that fraction and the limit a clump's
  // sphere may take (sim/guards.hpp) the run goes on past Hertz theory's small-overlap range.
  double deepest_overlap_fraction() const { return deepest_overlap_fraction_; }
  const std::vector<int>& body_contacts() const { return body_contacts_; }
  const GuardFailure& failure() const { return failure_; }
  const StepProfile& profile() const { return profile_; }
  double time_s() const { return time_s_; }
  std::uint64_t step_count() const { return step_; }
  std::size_t neighbour_builds() const { return contacts_.pairs.builds(); }
  std::size_t neighbour_pairs() const { return contacts_.pairs.pair_count(); }
  std::mt19937_64& rng() { return rng_; }

  double kinetic_energy_j() const;
  double potential_energy_j() const;
  // The work the moving walls have done on the particles since the energy guard's reference was
  // last taken (J; negative when the particles did work on the walls): sum over the steps of
  // -(F . v + T . w) dt, with F and T the force and torque the particles exert on the wall
  // (Wall::force_n, torque_n_m) and v, w its velocity over the step. A servo lid that compresses a
  // specimen stores its work as the contacts' elastic energy, which a collapsing force chain gives
  // back as kinetic energy: the energy guard counts it (check_guards()).
  double wall_work_j() const { return wall_work_j_; }
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
  void ensure_ready();
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
  // The contact pass's inputs (sim/contact_forces.hpp).
  ContactInputs contact_inputs() const;
  bool check_guards(bool energy_now = false);
  // Calls the frame observer with the current state (FrameObserver) and schedules the next frame.
  void emit_frame();
  double energy_budget_j() const;
  // The energy guard's reference, now: the budget, the potential energy and no walls' work yet.
  void take_energy_reference();
  void rebuild_lists();
  void update_work_shares();
  // Returns true when the bodies were renumbered (the neighbour lists are then rebuilt).
  bool sort_spatially();
  std::vector<std::uint32_t> thread_slabs(const Vec3& lo, const Vec3& hi) const;
  void reorder_bodies(const std::vector<std::uint32_t>& old_of_new);
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
  ContactPipeline contacts_;
  ThreadPlan threads_;
  StepStats stats_;
  double deepest_overlap_fraction_ = 0.0;
  std::vector<int> body_contacts_;
  // CDT (contact/rolling_cdt_torque.hpp): per body, the torque per unit of capacity that
  // compute_forces() settles on (the walls take their contacts' shares of it).
  std::vector<Vec3> cdt_torque_per_capacity_;
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
  double reference_energy_j_ = -1.0;  // < 0: recompute
  double reference_potential_j_ = 0.0;
  double wall_work_j_ = 0.0;  // since the reference (wall_work_j())
  bool ready_ = false;
  bool kick_pending_ = false;  // finish_kick() not yet applied
  double kick_dt_s_ = 0.0;     // the step it belongs to
};

}  // namespace seedcal
