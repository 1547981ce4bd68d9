#pragma once
// How the contact kernel (sim/contact_forces.cpp) splits one step's work between its threads.
//
// Both contact lists are ordered by body (the sphere pairs by the body of their first sphere), and
// each thread takes the pairs of one contiguous range of bodies from both: its sphere pairs, then
// its wall pairs. The ranges are cut where the work is equal, counting a listed wall pair as
// kWallPairWeight listed sphere pairs. So each thread reads and writes mostly the bodies it has
// just moved in the integrator's pass (ranges of bodies too; a body moved by another core costs a
// transfer between the cores' caches), and the bodies on the floor, which carry the wall pairs,
// are shared out like the others. A group (one body pair, or one body and one wall) is never
// split: the multi-contact correction counts its touching pairs. The cuts come from the lists
// alone, not from timing, so each thread adds up the same forces in the same order for a given
// state and thread count, and runs are reproducible. With one thread the share is everything, in
// list order.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace seedcal {

// A listed wall pair costs a shape query and, when it touches, a scalar contact; a listed sphere
// pair a distance test and, a third to a half of the time, a contact in the batch kernel. The
// weight is the ratio of the two costs per listed pair on the benchmark beds
// (docs/results/solver_speed.md).
inline constexpr double kWallPairWeight = 3.0;

struct WorkShare {
  std::size_t sphere_begin = 0, sphere_end = 0;  // sphere-sphere groups [begin, end)
  std::size_t wall_begin = 0, wall_end = 0;      // sphere-wall groups [begin, end)
  // The bodies whose groups these are: the force reduction's range too, so that a thread sums
  // the forces of the bodies whose contacts it computed first.
  std::size_t body_begin = 0, body_end = 0;
  // The bodies this share moves in the integrator's pass: equal sphere counts (the pass's cost
  // is per sphere), cut at body boundaries.
  std::size_t move_begin = 0, move_end = 0;
};

// One contact list: `start[g]` is group g's first pair (start[groups] the pair count) and
// body_of(g) its body, non-decreasing in g.
struct GroupedList {
  const std::vector<std::uint32_t>& start;
  std::size_t groups;
  std::function<std::uint32_t(std::size_t group)> body_of;
};

// The first group whose first pair is at or after pair index `pair` (groups when none is).
std::size_t group_at_or_after(const std::vector<std::uint32_t>& start, std::size_t groups,
                              std::size_t pair);

// `threads` shares of the two lists over `bodies` bodies, as above. The integrator's ranges
// (move_begin, move_end) are left to split_bodies_by_spheres().
std::vector<WorkShare> split_contact_work(const GroupedList& spheres, const GroupedList& walls,
                                          std::size_t bodies, std::size_t threads);

// Sets the shares' integrator ranges: consecutive body ranges with equal numbers of spheres, to
// within one body; body b owns spheres [first_sphere[b], first_sphere[b + 1]).
void split_bodies_by_spheres(const std::vector<std::uint32_t>& first_sphere, std::size_t bodies,
                             std::vector<WorkShare>& shares);

}  // namespace seedcal
