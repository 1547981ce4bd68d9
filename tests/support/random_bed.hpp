#pragma once
// A loose bed of spheres on a jittered lattice in a box of five planes, with random velocities
// drawn from the simulation's own generator (deterministic for a seed).
#include <random>

#include "tests/support/worlds.hpp"

namespace seedcal::testing {

struct BedSpec {
  int nx = 8, ny = 8, nz = 8;
  double radius_m = 0.002;
  double spacing = 2.2;     // lattice pitch in radii
  double jitter = 0.05;     // position jitter in radii
  double speed_m_s = 0.5;   // random velocity scale
  // Nonzero: every other sphere of the lattice (checkerboard) is of this material instead of 0.
  std::uint16_t second_material = 0;
};

inline void add_box_walls(Simulation& sim, double lx, double ly) {
  sim.add_wall(plane_wall(Vec3::Zero(), Vec3::UnitZ()));
  sim.add_wall(plane_wall(Vec3::Zero(), Vec3::UnitX()));
  sim.add_wall(plane_wall(Vec3(lx, 0, 0), -Vec3::UnitX()));
  sim.add_wall(plane_wall(Vec3::Zero(), Vec3::UnitY()));
  sim.add_wall(plane_wall(Vec3(0, ly, 0), -Vec3::UnitY()));
}

// The bed's spheres without walls, the lattice moved by `origin_m`.
inline void add_lattice_spheres(Simulation& sim, const BedSpec& b, double density_kg_m3,
                                const Vec3& origin_m = Vec3::Zero()) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto& rng = sim.rng();
  const double pitch = b.spacing * b.radius_m;
  for (int k = 0; k < b.nz; ++k)
    for (int j = 0; j < b.ny; ++j)
      for (int i = 0; i < b.nx; ++i) {
        const bool second = b.second_material != 0 && (i + j + k) % 2 == 1;
        BodyDef d = sphere_body(b.radius_m, density_kg_m3, second ? b.second_material : 0);
        d.position_m = origin_m + Vec3((i + 0.5) * pitch, (j + 0.5) * pitch, (k + 0.5) * pitch) +
                       b.jitter * b.radius_m * Vec3(u(rng), u(rng), u(rng));
        d.velocity_m_s = b.speed_m_s * Vec3(u(rng), u(rng), u(rng));
        sim.add_body(d);
      }
}

inline void add_random_bed(Simulation& sim, const BedSpec& b, double density_kg_m3) {
  add_lattice_spheres(sim, b, density_kg_m3);
  const double pitch = b.spacing * b.radius_m;
  add_box_walls(sim, b.nx * pitch, b.ny * pitch);
}

}  // namespace seedcal::testing
