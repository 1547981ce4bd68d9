#pragma once
// How a Simulation's step is shared between its threads: the shares of the work (which bodies
// each thread moves, whose contacts it computes and whose forces it sums; sim/work_split.hpp) and
// each thread's own buffers (force accumulators, the marks of what it wrote, the walls' shares,
// CDT's wall shares, the contact kernel's scratch). Every thread writes only its own buffers; the
// force reduction sums them in thread order, so a result depends on the thread count but not on
// the threads' timing.
#include <cstdint>
#include <limits>
#include <vector>

#include "solver/core/body_state.hpp"
#include "solver/sim/contact_view.hpp"
#include "solver/sim/kernel_scratch.hpp"
#include "solver/sim/work_split.hpp"

namespace seedcal {

class VerletList;
class WallContactList;

// CDT (contact/rolling_cdt.hpp): a wall contact's share of its body's rolling-torque capacity;
// the wall takes the reaction of that share of the body's torque.
struct CdtWallShare {
  std::uint32_t wall, body;
  double capacity_n_m;
};

struct ThreadPlan {
  // Grows the per-thread buffers to `threads` threads, `bodies` bodies and `walls` walls. The
  // accumulators are zero between steps (the force reduction clears what it reads), so new ones
  // start at zero too.
  void size(int threads, std::size_t bodies, std::size_t walls);
  // Recomputes the shares when the lists changed since the last call (`lists_version` counts
  // rebuilds and renumberings; adding or removing bodies always ends in one).
  void update_shares(std::uint64_t lists_version, int threads, const BodyState& bodies,
                     const SphereState& spheres, const VerletList& pairs,
                     const WallContactList& wall_pairs);
  // Clears the body pass's per-thread results for a step.
  void start_step(int threads);

  std::vector<WorkShare> shares;
  // Per thread: force, torque and rolling-capacity accumulators (at least one per body).
  std::vector<std::vector<BodyAccumulator>> body_acc;
  // Per thread, 1 for a body whose accumulator the thread wrote this step: the reduction reads
  // only those (a thread's contacts reach few of the other threads' bodies) and clears them.
  std::vector<std::vector<std::uint8_t>> body_touched;
  std::vector<std::vector<WallAccumulator>> wall_acc;
  std::vector<BodyAccumulator*> acc_ptr;     // body_acc[t].data()
  std::vector<std::uint8_t*> touched_ptr;    // body_touched[t].data()
  std::vector<std::vector<CdtWallShare>> cdt_wall;
  std::vector<KernelScratch> scratch;        // the contact kernel's buffers
  // The body pass's largest squared sphere displacement and lowest bad body, per thread.
  std::vector<double> moved_sq;
  std::vector<std::int64_t> bad;

 private:
  std::uint64_t shares_version_ = std::numeric_limits<std::uint64_t>::max();
};

}  // namespace seedcal
