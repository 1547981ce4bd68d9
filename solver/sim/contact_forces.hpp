#pragma once
// Internal interface between the Simulation and its contact force pass.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "solver/contact/contact_model.hpp"
#include "solver/core/body_state.hpp"
#include "solver/core/materials.hpp"
#include "solver/sim/pair_batch.hpp"
#include "solver/sim/simulation_options.hpp"
#include "solver/walls/wall.hpp"

namespace seedcal {

struct ContactPipeline;
struct ThreadPlan;

// What the contact pass reads of the Simulation; its lists, views and history are in the
// ContactPipeline, the threads' shares and buffers in the ThreadPlan.
struct ContactInputs {
  const SimulationOptions& options;
  const InteractionTable& table;
  const BodyState& bodies;
  const SphereState& spheres;
  const std::vector<Wall>& walls;
};

struct ThreadStats {
  std::size_t sphere_contacts = 0, wall_contacts = 0;
  double max_overlap = 0.0, max_fn = 0.0;
  // Overlap / smaller radius past which a pair's limit (sim/overlap_limits.hpp) is looked up
  // (overlap_prefilter_fraction), and what those pairs left.
  double prefilter = 0.5;
  DeepOverlap deep;
  // Called for every touching pair: two compares on the hot path, the divisions only when the
  // overlap is deep enough for its limit to matter.
  void note(double overlap, double fn, double r_min, double limit, std::int64_t body) {
    max_overlap = std::max(max_overlap, overlap);
    max_fn = std::max(max_fn, fn);
    if (overlap > prefilter * r_min) deep.note(overlap, r_min, limit, body);
  }
};

// One step's contact forces: set up once by one thread (prepare_contact_pass), then run by every
// thread of a team on its shares of the lists (run_contact_pass, inside the step's parallel
// region; Simulation::work_shares_, sim/work_split.hpp), then combined (finish_contact_pass).
// Each thread writes its forces and torques to its own accumulators; the force reduction sums
// them in thread order. Records the number of touching sphere pairs per group.
struct ContactPass {
  NormalModel normal = NormalModel::hertz_mindlin;
  RollingModel rolling = RollingModel::none;
  bool count_groups = false;  // touching pairs per group recorded (HMNR, tracked contacts)
  PairBatchArgs batch;
  PairBatchFn batch_fn = nullptr;
  WallBatchArgs wall_args;
  WallBatchFn wall_fn = nullptr;
  std::vector<BatchPairConstants> batch_constants;  // packed once: the table is fixed
  std::vector<ThreadStats> stats;                   // one per thread
};

// The serial set-up of a step's pass, in `contacts.pass`.
void prepare_contact_pass(const ContactInputs& in, ContactPipeline& contacts);
// The table's constants as the batch kernels read them: material pair (i, j) at i * count + j.
std::vector<BatchPairConstants> pack_batch_constants(const InteractionTable& table);
// Thread `thread` of a team of `team`: its shares' sphere and wall contacts.
void run_contact_pass(const ContactInputs& in, ContactPipeline& contacts, ThreadPlan& plan,
                      int thread, int team);
ThreadStats finish_contact_pass(const ContactPass& pass);

}  // namespace seedcal
