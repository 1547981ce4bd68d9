#pragma once
// Candidate sphere-wall contacts within the Verlet skin, with per-contact history keyed by
// (body, wall, sphere, primitive) and grouped by (body, wall) for the multi-contact correction.
// Rebuilt together with the sphere-sphere list.
#include <cstdint>
#include <vector>

#include "solver/core/body_state.hpp"
#include "solver/walls/wall.hpp"

namespace seedcal {

class WallContactList {
 public:
  void build(const SphereState& spheres, const std::vector<Wall>& walls, double skin_m,
             bool keep_rolling);

  // As VerletList::renumber: carry the history over to renumbered spheres (new = new_of_old[old]).
  void renumber(const std::vector<std::uint32_t>& new_of_old, const SphereState& spheres);

  std::size_t size() const { return sphere_.size(); }
  std::size_t group_count() const { return group_start_.empty() ? 0 : group_start_.size() - 1; }
  const std::vector<std::uint32_t>& sphere() const { return sphere_; }
  const std::vector<std::uint16_t>& wall() const { return wall_; }
  const std::vector<std::uint32_t>& primitive() const { return primitive_; }
  const std::vector<std::uint32_t>& group_start() const { return group_start_; }
  std::vector<Vec3>& tangential() { return tangential_; }
  std::vector<Vec3>& rolling() { return rolling_; }

 private:
  std::vector<std::uint32_t> sphere_, primitive_, group_start_;
  std::vector<std::uint16_t> wall_;
  std::vector<Vec3> tangential_, rolling_;
};

// World sphere centre expressed in a wall's frame, and back.
inline Vec3 to_wall_frame(const WallPose& pose, const Vec3& p) {
  return pose.orientation.conjugate() * (p - pose.origin_m);
}

}  // namespace seedcal
