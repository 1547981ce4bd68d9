#include "solver/sim/thread_plan.hpp"

#include <algorithm>

#include "solver/broadphase/verlet_list.hpp"
#include "solver/walls/wall_contact_list.hpp"

namespace seedcal {

void ThreadPlan::size(int threads, std::size_t bodies, std::size_t walls) {
  const auto t = static_cast<std::size_t>(std::max(1, threads));
  BodyAccumulator zero;
  zero.force_n.setZero();
  zero.torque_n_m.setZero();
  zero.roll_capacity_n_m = 0.0;
  body_acc.resize(t);
  for (auto& acc : body_acc)
    if (acc.size() < bodies) acc.resize(bodies, zero);
  body_touched.resize(t);
  for (auto& touched : body_touched)
    if (touched.size() < bodies) touched.resize(bodies, 0);
  wall_acc.assign(t, std::vector<WallAccumulator>(walls));
  acc_ptr.resize(t);
  touched_ptr.resize(t);
  for (std::size_t k = 0; k < t; ++k) {
    acc_ptr[k] = body_acc[k].data();
    touched_ptr[k] = body_touched[k].data();
  }
  cdt_wall.resize(t);
  scratch.resize(t);
}

void ThreadPlan::update_shares(std::uint64_t lists_version, int threads, const BodyState& bodies,
                               const SphereState& spheres, const VerletList& pairs,
                               const WallContactList& wall_pairs) {
  if (shares_version_ == lists_version) return;
  const auto nt = static_cast<std::size_t>(std::max(1, threads));
  const std::size_t nb = bodies.size();
  const std::uint32_t* body_of_sphere = spheres.body.data();
  const auto& gs = pairs.group_start();
  const auto& si = pairs.si();
  const auto& wgs = wall_pairs.group_start();
  const auto& ws = wall_pairs.sphere();
  shares = split_contact_work(
      {gs, pairs.group_count(), [&](std::size_t g) { return body_of_sphere[si[gs[g]]]; }},
      {wgs, wall_pairs.group_count(), [&](std::size_t g) { return body_of_sphere[ws[wgs[g]]]; }},
      nb, nt);
  split_bodies_by_spheres(bodies.first_sphere, nb, shares);
  shares_version_ = lists_version;
}

void ThreadPlan::start_step(int threads) {
  const auto nt = static_cast<std::size_t>(std::max(1, threads));
  moved_sq.assign(nt, 0.0);
  bad.assign(nt, std::numeric_limits<std::int64_t>::max());
}

}  // namespace seedcal
