#pragma once
// The contact pipeline of a Simulation: the neighbour lists with their contact history
// (broadphase/verlet_list.hpp, walls/wall_contact_list.hpp), the packed views the kernel reads
// (sim/contact_view.hpp), the kernel's per-step set-up (sim/contact_forces.hpp) and the touching
// pairs per group it counts. The contact law itself is contact/contact_law.hpp.
#include <cstdint>
#include <vector>

#include "solver/broadphase/verlet_list.hpp"
#include "solver/core/body_state.hpp"
#include "solver/sim/contact_forces.hpp"
#include "solver/sim/contact_view.hpp"
#include "solver/walls/wall.hpp"
#include "solver/walls/wall_contact_list.hpp"

namespace seedcal {

struct ContactPipeline {
  // Rebuilds both lists with the skin `skin_m`, carrying the history over; rolling-spring history
  // only when `rolling_history` (EPSD).
  void rebuild(const SphereState& spheres, const std::vector<Wall>& walls, bool rolling_history,
               int threads);
  // Spheres and walls each may use half the skin before a pair can be missed; a wall's share is
  // bounded by how far its surface moved since the last build.
  bool walls_moved_beyond_skin(const std::vector<Wall>& walls) const;
  // Rebuilds the views from the state, with dashpot velocities predicted over h (0: the
  // velocities are at the force time).
  void refresh_views(const BodyState& bodies, const SphereState& spheres, double h, int threads);
  // Sphere-level contacts per body at the last force pass (from the groups' counts).
  void count_body_contacts(const SphereState& spheres, std::size_t bodies,
                           std::vector<int>& out) const;

  double skin_m = 0.0;
  VerletList pairs;
  WallContactList wall_pairs;
  // Touching pairs per group of each list at the last force pass (sphere groups only when
  // counted: HMNR or tracked contacts).
  std::vector<int> sphere_group_touch, wall_group_touch;
  std::vector<SphereView> sphere_view;
  // Each sphere's deepest allowed overlap, m (sim/overlap_limits.hpp), set with the lists.
  std::vector<double> overlap_limit_m;
  std::vector<BodyView> body_view;
  ContactPass pass;
  // Counts rebuilds and renumberings (ThreadPlan::update_shares).
  std::uint64_t lists_version = 0;
  // The material every sphere is of, set with the lists (spheres come and go only with a
  // rebuild); -1 when they differ. Then every sphere pair has the same constants.
  int one_sphere_material = -1;

 private:
  std::vector<WallPose> wall_pose_at_build_;
};

}  // namespace seedcal
