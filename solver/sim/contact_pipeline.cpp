#include "solver/sim/contact_pipeline.hpp"

#include <algorithm>

#include "solver/walls/wall.hpp"


namespace seedcal {

void ContactPipeline::rebuild(const SphereState& spheres, const std::vector<Wall>& walls,
                              bool rolling_history, int threads) {
  pairs.build(spheres, skin_m, rolling_history, threads);
  wall_pairs.build(spheres, walls, skin_m, rolling_history);
  wall_pose_at_build_.clear();
  for (const Wall& w : walls) wall_pose_at_build_.push_back(w.pose);
  one_sphere_material = -1;
  if (!spheres.material.empty() &&
      std::all_of(spheres.material.begin(), spheres.material.end(),
                  [&](std::uint16_t m) { return m == spheres.material.front(); }))
    one_sphere_material = spheres.material.front();
  ++lists_version;
}

bool ContactPipeline::walls_moved_beyond_skin(const std::vector<Wall>& walls) const {
  for (std::size_t w = 0; w < walls.size(); ++w) {
    if (!walls[w].motion) continue;
    if (surface_displacement_m(*walls[w].shape, wall_pose_at_build_[w], walls[w].pose) >
        0.5 * skin_m)
      return true;
  }
  return false;
}

void ContactPipeline::refresh_views(const BodyState& bodies, const SphereState& spheres, double h,
                                    int threads) {
  const std::size_t nb = bodies.size(), ns = spheres.size();
  body_view.resize(nb);
  sphere_view.resize(ns);
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
  for (std::size_t b = 0; b < nb; ++b) {
    const Vec3 w_end =
        h == 0.0 ? bodies.angular_velocity[b]
                 : angular_velocity_from_momentum(
                       bodies.orientation[b], bodies.inv_inertia[b],
                       Vec3(bodies.angular_momentum[b] + h * bodies.torque_n_m[b]),
                       bodies.isotropic[b] != 0);
    fill_body_view(body_view[b], bodies.velocity_m_s[b], bodies.angular_velocity[b], w_end,
                   bodies.force_n[b], bodies.inv_mass[b], h, bodies.position_m[b]);
    for (std::uint32_t i = bodies.first_sphere[b]; i < bodies.first_sphere[b + 1]; ++i)
      fill_sphere_view(sphere_view[i], spheres.position_m[i], spheres.radius_m[i]);
  }
}

void ContactPipeline::count_body_contacts(const SphereState& spheres, std::size_t bodies,
                                          std::vector<int>& out) const {
  out.assign(bodies, 0);
  const auto& gs = pairs.group_start();
  for (std::size_t k = 0; k < sphere_group_touch.size(); ++k) {
    if (sphere_group_touch[k] == 0) continue;
    const std::uint32_t p = gs[k];
    out[spheres.body[pairs.si()[p]]] += sphere_group_touch[k];
    out[spheres.body[pairs.sj()[p]]] += sphere_group_touch[k];
  }
  const auto& wgs = wall_pairs.group_start();
  for (std::size_t k = 0; k < wall_group_touch.size(); ++k)
    out[spheres.body[wall_pairs.sphere()[wgs[k]]]] += wall_group_touch[k];
}

}  // namespace seedcal
