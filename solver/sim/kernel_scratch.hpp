#pragma once
// One thread's working buffers in the contact kernel (sim/contact_forces.cpp), kept by the
// Simulation between steps: a step then allocates, zeroes and regrows nothing (on the clump bed
// the wall contacts alone regrew a 32 KB buffer every step on every thread).
#include <cstdint>
#include <vector>

#include "solver/core/vec.hpp"
#include "solver/sim/pair_batch.hpp"

namespace seedcal {

// The wall's side of a sphere-wall contact: the wall and the contact point minus the wall frame's
// origin (the lever of the wall's torque).
struct WallSide {
  std::uint32_t wall;
  Vec3 arm_m;
};

// 64-byte aligned: the vectors' records of two threads never share a cache line.
struct alignas(64) KernelScratch {
  std::vector<std::uint32_t> touch_k;     // a chunk's touching pairs, in list order
  std::vector<double> touch_scale;        // HMNR: each touching pair's damping scale
  std::vector<WallContactIn> wall_in;     // touching sphere-wall contacts of a batch
  std::vector<double> wall_scale;         // their damping scales (1, or HMNR's)
  std::vector<WallRollingIn> wall_rolling;  // EPSD: their rolling springs' inputs
  std::vector<WallContactOut> wall_out;
  std::vector<WallSide> wall_side;
};

}  // namespace seedcal
