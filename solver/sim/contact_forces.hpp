#pragma once
// Internal interface between the Simulation and its contact force kernel.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "solver/contact/contact_model.hpp"

namespace seedcal {

class Simulation;

struct ThreadStats {
  std::size_t sphere_contacts = 0, wall_contacts = 0;
  double max_overlap = 0.0, max_fn = 0.0;
  double worst_ratio = 0.0;  // overlap / smaller radius, recorded only above `ratio_limit`
  std::int64_t worst_body = -1;
  double worst_radius = 0.0;  // the smaller radius of the worst pair
  double ratio_limit = 0.5;
  // Called for every touching pair: two compares on the hot path, the division only when the
  // overlap guard is about to trip.
  void note(double overlap, double fn, double r_min, std::int64_t body) {
    max_overlap = std::max(max_overlap, overlap);
    max_fn = std::max(max_fn, fn);
    if (overlap > ratio_limit * r_min) {
      const double ratio = overlap / r_min;
      if (ratio > worst_ratio) { worst_ratio = ratio; worst_body = body; worst_radius = r_min; }
    }
  }
};

// Computes all contact forces and torques into the simulation's per-thread buffers; records the
// number of touching sphere pairs per group.
void run_force_kernel(Simulation& s, NormalModel nm, RollingModel rm,
                      std::vector<int>& sphere_group_touch, std::vector<int>& wall_group_touch,
                      ThreadStats& total);

}  // namespace seedcal
