#pragma once
// Spheres of a clump that can never touch anything. A sphere wholly inside another sphere of the
// same clump (|c_i - c_j| + r_i <= r_j) adds no surface and no volume, yet the stable time step
// follows the smallest sphere (the Rayleigh step is proportional to the radius,
// sim/time_step.hpp), so it slows every run of the clump for nothing. The paper places every
// sphere of its hand-made models "tangent to the outlines of the ellipsoid as far as possible"
// (seed-paper.txt, the filling of the MS models): none is buried.
#include <cstddef>
#include <vector>

#include "solver/clump/mass_properties.hpp"

namespace seedcal {

struct BuriedSphere {
  std::size_t sphere = 0;  // index of the buried sphere
  std::size_t inside = 0;  // index of the sphere that holds it
  // How far the buried sphere reaches out of the other, over its radius: (d + r_i - r_j) / r_i;
  // <= 0 when wholly inside.
  double protrusion_fraction = 0.0;
};

// Every sphere i that reaches at most `tolerance_fraction` x r_i out of some other sphere j of the
// clump: (|c_i - c_j| + r_i - r_j) / r_i <= tolerance_fraction. Of two equal spheres at (nearly)
// the same place only the later one is reported. One entry per buried sphere (the sphere it reaches
// least out of), in index order. O(N log N + N k), k the spheres within reach along x.
std::vector<BuriedSphere> buried_spheres(const std::vector<SphereXYZR>& spheres,
                                         double tolerance_fraction = 0.01);

// (|c_i - c_j| + r_i - r_j) / r_i: how far sphere i reaches out of sphere j, over r_i.
double protrusion_fraction(const SphereXYZR& i, const SphereXYZR& j);

// n unit vectors spread evenly over the sphere (the Fibonacci lattice: Gonzalez, "Measurement of
// areas on a sphere using Fibonacci and latitude-longitude lattices", Math. Geosci. 42, 2010).
std::vector<Vec3> fibonacci_directions(int n);

// How far sphere i reaches out of the union of all the other spheres, over r_i: the largest
// distance from that union (min_j |x - c_j| - r_j, exact for a union of spheres) of the points
// c_i + r_i u, u over `directions`. A lower bound of the true reach that tends to it as the
// directions fill the sphere; <= 0 when the others together cover sphere i (no single one need
// hold it). O(N |directions|).
double union_reach_fraction(const std::vector<SphereXYZR>& spheres, std::size_t i,
                            const std::vector<Vec3>& directions);

}  // namespace seedcal
