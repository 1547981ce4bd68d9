#pragma once
// Verlet neighbour list of sphere pairs from different bodies, with per-pair contact history.
//
// Pairs are grouped by body pair (body_i < body_j) and ordered by (body_i, body_j, sphere_i,
// sphere_j): the multi-contact correction needs the number of touching sphere pairs of each body
// pair, and the ordering makes the list (and so every result) independent of the thread count.
// History (tangential spring, rolling spring) is carried across rebuilds by a linear merge on the
// same key. The list is rebuilt only when some sphere moved more than half the skin.
//
// Candidates come from a cell grid of the spheres, or, when bodies hold many spheres, in two
// levels: the bodies whose bounding spheres come within the skin, then the sphere pairs of each
// such body pair that lie near the other body (the same list either way).
#include <cstdint>
#include <vector>

#include "solver/broadphase/cell_grid.hpp"
#include "solver/broadphase/pair_search.hpp"
#include "solver/core/body_state.hpp"

namespace seedcal {

// The bodies' bounding spheres and sphere ranges, for the two-level search.
struct BodyBounds {
  std::vector<Vec3> centre_m;
  std::vector<double> radius_m;
  std::vector<std::uint32_t> first;  // body b's spheres: first[b] .. first[b + 1] - 1
};

class VerletList {
 public:
  void set_search(PairSearch s) { search_ = s; }
  // `keep_rolling`: allocate rolling-spring history (EPSD only). The result does not depend on
  // `threads` (chunks are concatenated in body order).
  void build(const SphereState& spheres, double skin_m, bool keep_rolling, int threads = 1);
  // After the spheres were renumbered (new index = new_of_old[old index]; `spheres` is the new
  // state), carries the history over to the new numbering and re-sorts it by the new key, so the
  // next build() merges it as usual. A pair whose body order flips swaps i and j and negates its
  // history (the tangential spring of i relative to j is minus that of j relative to i).
  void renumber(const std::vector<std::uint32_t>& new_of_old, const SphereState& spheres);

  std::size_t pair_count() const { return si_.size(); }
  std::size_t group_count() const { return group_start_.empty() ? 0 : group_start_.size() - 1; }
  const std::vector<std::uint32_t>& si() const { return si_; }
  const std::vector<std::uint32_t>& sj() const { return sj_; }
  const std::vector<std::uint32_t>& group_start() const { return group_start_; }
  std::vector<Vec3>& tangential() { return tangential_; }
  std::vector<Vec3>& rolling() { return rolling_; }
  // Per pair: 1 when its tangential (or rolling) spring may be non-zero (it touched at the last
  // force pass), 0 when the springs are zero. The batched force pass keeps it (sim/contact_forces.cpp) and clears
  // only the springs of pairs that came apart, instead of rewriting every listed pair's spring at
  // every step; build() and renumber() set it from the springs they carry over.
  std::vector<std::uint8_t>& live() { return live_; }
  std::size_t builds() const { return builds_; }
  double skin_m() const { return skin_m_; }
  // The skin check (done by the integrator's body pass, which already has every centre): the list
  // must be rebuilt when a sphere moved more than half the skin since the last build, i.e. by more
  // than rebuild_distance_sq() squared, or when built_at() is empty (after renumber()).
  const std::vector<Vec3>& built_at() const { return built_at_; }
  double rebuild_distance_sq() const { return 0.25 * skin_m_ * skin_m_; }

 private:
  CellGrid grid_;      // of the spheres, or of the bodies' bounding spheres (two-level search)
  BodyBounds bodies_;  // two-level search: each body's bounding sphere and spheres
  std::vector<std::uint32_t> si_, sj_, group_start_;
  std::vector<Vec3> tangential_, rolling_;
  std::vector<std::uint8_t> live_;
  std::vector<Vec3> built_at_;  // sphere centres at the last build
  void mark_live();
  double skin_m_ = 0.0;
  std::size_t builds_ = 0;
  PairSearch search_ = PairSearch::automatic;
};

}  // namespace seedcal
