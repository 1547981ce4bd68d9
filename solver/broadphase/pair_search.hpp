#pragma once
// How the Verlet list finds candidate sphere pairs (broadphase/verlet_list.cpp): by its rule (a
// grid of spheres, or in two levels when bodies hold many spheres), or always one way (tests and
// benchmarks). The list, and so every result, is the same whichever way.
namespace seedcal {

enum class PairSearch { automatic, sphere_grid, two_level };

}  // namespace seedcal
