// Re-sorting bodies along a Morton (Z-order) curve of their centres, so that bodies near in space
// are near in memory: the contact kernel then finds a neighbour's data in cache instead of in main
// memory (LIGGGHTS's atom_modify sort, DEM-Engine's periodic re-ordering). With several threads
// the curve runs within one slab of the bed per thread (thread_slabs()), as a domain decomposition
// would cut it, so that the threads' bodies meet over one plane.
#include <algorithm>
#include <cmath>
#include <numeric>

#include "solver/sim/simulation.hpp"

namespace seedcal {
namespace {

// Interleaves the low 21 bits of x, y, z.
std::uint64_t morton3(std::uint32_t x, std::uint32_t y, std::uint32_t z) {
  auto spread = [](std::uint64_t v) {
    v &= 0x1fffff;
    v = (v | v << 32) & 0x1f00000000ffffULL;
    v = (v | v << 16) & 0x1f0000ff0000ffULL;
    v = (v | v << 8) & 0x100f00f00f00f00fULL;
    v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
    v = (v | v << 2) & 0x1249249249249249ULL;
    return v;
  };
  return spread(x) | spread(y) << 1 | spread(z) << 2;
}

template <class T>
void permute(std::vector<T>& v, const std::vector<std::uint32_t>& old_of_new) {
  std::vector<T> out(old_of_new.size());
  for (std::size_t k = 0; k < old_of_new.size(); ++k) out[k] = v[old_of_new[k]];
  v.swap(out);
}

}  // namespace

// With T > 1 threads, the bodies cut into T slabs across the longest side of their bounding box
// that is not along gravity, each holding 1/T of the spheres (sim/work_split.hpp gives each thread
// equal sphere counts in index order, so a slab is a thread's share of the body pass). The curve
// then orders each slab. A thread's bodies meet the next thread's over one plane: the bodies with
// pairs across it are the ones whose records cross between the cores every step
// (tests/bench/README.md), and a plane across the longest side is the smallest such face for a
// box-shaped bed. The curve's own halves meet over a staircase of its cells. With one thread: one
// slab, the curve alone.
std::vector<std::uint32_t> Simulation::thread_slabs(const Vec3& lo, const Vec3& hi) const {
  const std::size_t nb = bodies_.size();
  const std::size_t slabs = static_cast<std::size_t>(std::max(1, options_.threads));
  std::vector<std::uint32_t> slab(nb, 0);
  if (slabs == 1) return slab;
  // Across the longest side that is not along gravity: a bed under gravity is dense at the bottom
  // and dilute above, so a cut across the height would give one thread most of the contacts and
  // the contact pass's shares (cut where the contact work is equal) would not be the slabs.
  Vec3 extent = hi - lo;
  const Vec3& g = options_.gravity_m_s2;
  if (g.squaredNorm() > 0.0) {
    int down = 0;
    g.cwiseAbs().maxCoeff(&down);
    extent[down] = -1.0;
  }
  int axis = 0;
  extent.maxCoeff(&axis);
  std::vector<std::uint32_t> along(nb);
  std::iota(along.begin(), along.end(), 0u);
  std::stable_sort(along.begin(), along.end(), [&](std::uint32_t a, std::uint32_t b) {
    return bodies_.position_m[a][axis] < bodies_.position_m[b][axis];
  });
  const std::size_t spheres = spheres_.radius_m.size();
  std::size_t before = 0;  // spheres of the bodies ahead in `along`
  for (const std::uint32_t b : along) {
    slab[b] = static_cast<std::uint32_t>(std::min(slabs - 1, before * slabs / spheres));
    before += bodies_.first_sphere[b + 1] - bodies_.first_sphere[b];
  }
  return slab;
}

bool Simulation::sort_spatially() {
  const std::size_t nb = bodies_.size();
  Vec3 lo = bodies_.position_m[0], hi = lo;
  for (const Vec3& p : bodies_.position_m) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  double r_max = 0.0;
  for (double r : spheres_.radius_m) r_max = std::max(r_max, r);
  const double cell = std::max(2.0 * r_max, (hi - lo).maxCoeff() / 2e6);
  std::vector<std::uint64_t> key(nb);
  for (std::size_t b = 0; b < nb; ++b) {
    const Vec3 c = (bodies_.position_m[b] - lo) / cell;
    key[b] = morton3(static_cast<std::uint32_t>(c.x()), static_cast<std::uint32_t>(c.y()),
                     static_cast<std::uint32_t>(c.z()));
  }
  const std::vector<std::uint32_t> slab = thread_slabs(lo, hi);
  std::vector<std::uint32_t> old_of_new(nb);
  std::iota(old_of_new.begin(), old_of_new.end(), 0u);
  std::stable_sort(old_of_new.begin(), old_of_new.end(), [&](std::uint32_t a, std::uint32_t b) {
    return slab[a] != slab[b] ? slab[a] < slab[b] : key[a] < key[b];
  });
  bool identity = true;
  for (std::size_t k = 0; k < nb && identity; ++k) identity = old_of_new[k] == k;
  if (identity) return false;

  reorder_bodies(old_of_new);
  return true;
}

// Keeps the bodies listed in old_of_new, in that order; any body not listed is removed. Spheres
// follow their bodies; contact history is renumbered and the history of removed spheres dropped.
void Simulation::reorder_bodies(const std::vector<std::uint32_t>& old_of_new) {
  const std::size_t nb = old_of_new.size();
  constexpr std::uint32_t kGone = 0xffffffffu;
  const SphereState old = spheres_;
  std::vector<std::uint32_t> sphere_new_of_old(old.size(), kGone);
  std::vector<std::uint32_t> first{0};
  SphereState ns;
  for (std::size_t nbody = 0; nbody < nb; ++nbody) {
    const std::uint32_t ob = old_of_new[nbody];
    for (std::uint32_t s = bodies_.first_sphere[ob]; s < bodies_.first_sphere[ob + 1]; ++s) {
      sphere_new_of_old[s] = static_cast<std::uint32_t>(ns.radius_m.size());
      ns.body.push_back(static_cast<std::uint32_t>(nbody));
      ns.offset_body_m.push_back(old.offset_body_m[s]);
      ns.radius_m.push_back(old.radius_m[s]);
      ns.material.push_back(old.material[s]);
      ns.position_m.push_back(old.position_m[s]);
    }
    first.push_back(static_cast<std::uint32_t>(ns.radius_m.size()));
  }
  spheres_ = std::move(ns);
  bodies_.first_sphere = std::move(first);
  permute(bodies_.position_m, old_of_new);
  permute(bodies_.orientation, old_of_new);
  permute(bodies_.velocity_m_s, old_of_new);
  permute(bodies_.angular_momentum, old_of_new);
  permute(bodies_.angular_velocity, old_of_new);
  permute(bodies_.mass_kg, old_of_new);
  permute(bodies_.inv_mass, old_of_new);
  permute(bodies_.principal_inertia, old_of_new);
  permute(bodies_.inv_inertia, old_of_new);
  permute(bodies_.isotropic, old_of_new);
  permute(bodies_.id, old_of_new);
  permute(bodies_.force_n, old_of_new);
  permute(bodies_.torque_n_m, old_of_new);
  std::fill(index_of_id_.begin(), index_of_id_.end(), kGone);
  for (std::size_t b = 0; b < nb; ++b) index_of_id_[bodies_.id[b]] = static_cast<std::uint32_t>(b);
  if (ready_) {
    contacts_.pairs.renumber(sphere_new_of_old, spheres_);
    contacts_.wall_pairs.renumber(sphere_new_of_old, spheres_);
    threads_.size(options_.threads, bodies_.size(), walls_.size());
    rebuild_lists();
  }
}

void Simulation::remove_bodies(const std::function<bool(std::uint32_t index)>& remove) {
  settle();
  std::vector<std::uint32_t> keep;
  for (std::uint32_t b = 0; b < bodies_.size(); ++b)
    if (!remove(b)) keep.push_back(b);
  if (keep.size() == bodies_.size()) return;
  reorder_bodies(keep);
  reference_energy_j_ = -1.0;
  if (ready_) take_energy_reference();
}

}  // namespace seedcal
