#pragma once
// The two throughput benchmarks, the same scenes as the LIGGGHTS decks in
// shared/bench/liggghts/ (in.settled_bed, in.clump_bed): same sizes, materials, box, insertion
// region, settling protocol and 20,000 timed steps at dt = 1e-6 s.
//
//   settled bed: 10,000 spheres r = 2 mm in a 0.1 x 0.1 m box (planes x, y = 0 and 0.1, floor
//                z = 0), inserted at random non-overlapping positions in
//                [0.0025, 0.0975]^2 x [0.0025, 0.1975], settled 80,000 steps at 5e-6 s.
//   clump bed:   1,000 nine-sphere clumps (data/bench/clump9.txt) inserted at random poses in
//                [0.006, 0.094]^2 x [0.006, 0.294], settled 100,000 steps at 5e-6 s.
//   fine clump bed (tests/bench/in.fine_clump_bed): 100 clumps of the automatic 164-sphere
//                model (data/clumps/jinong1-auto-s2.toml; spheres 0.55 to 4.07 mm) in a
//                0.05 x 0.05 m box, inserted in [0.006, 0.044]^2 x [0.006, 0.144], settled
//                160,000 steps at 2.5e-6 s (about 0.3 of the smallest sphere's Rayleigh time).
// Materials: E 165 MPa, nu 0.4, e 0.45, mu 0.55, mu_r 0.05, rho 1340 kg/m3 (walls alike),
// Hertz-Mindlin with tangential history and CDT rolling friction (seedcal's CDT uses each body's
// own spin, LIGGGHTS's the relative spin and R*); Verlet skin 0.4 mm as the decks' `neighbor`.
#include <cstdint>
#include <string>
#include <vector>

#include "solver/broadphase/pair_search.hpp"
#include "solver/clump/mass_properties.hpp"
#include "solver/core/vec.hpp"

namespace seedcal {

struct BenchSpec {
  std::string name;              // "settled-bed", "clump-bed" or "fine-clump-bed"
  std::vector<SphereXYZR> clump; // the clump beds' template (empty: 2 mm spheres)
  std::size_t bodies = 10000;
  double box_xy_m = 0.1;         // side of the square box
  Vec3 region_lo_m = Vec3(0.0025, 0.0025, 0.0025), region_hi_m = Vec3(0.0975, 0.0975, 0.1975);  // insertion
  double settle_dt_s = 5e-6;
  std::uint64_t settle_steps = 0;
  std::uint64_t timed_steps = 20000;
  int threads = 1;
  std::uint64_t seed = 1;
  int simd_lanes = 8;            // widest contact kernel allowed (SimulationOptions::simd_lanes)
  PairSearch pair_search = PairSearch::automatic;  // SimulationOptions::pair_search
};

struct BenchResult {
  std::size_t spheres = 0, bodies = 0;
  std::uint64_t steps = 0;       // timed steps
  double wall_seconds = 0.0;     // timed steps only
  double settle_wall_seconds = 0.0;
  double sphere_steps_per_second = 0.0;
  double contacts_per_sphere = 0.0;  // (2 sphere-sphere + sphere-wall contacts) / spheres
  std::size_t neighbour_builds = 0;  // during the timed steps
  int kernel_lanes = 1;              // lanes of the contact kernel that ran (1, 4 or 8)
  double kinetic_energy_j = 0.0;
  std::string failure;           // empty when the run completed
  double integrate_s = 0, neighbour_s = 0, contact_s = 0, reduce_s = 0;  // timed-step profile
  // At the end: bodies touching a body that another thread moves (the threads' shares of the body
  // pass, sim/work_split.hpp). Their records cross between the cores' caches every step.
  std::size_t bodies_across_threads = 0;
};

BenchSpec settled_bed_spec();
BenchSpec clump_bed_spec(std::vector<SphereXYZR> clump);
BenchSpec fine_clump_bed_spec(std::vector<SphereXYZR> clump);
BenchResult run_bench(const BenchSpec& spec);

}  // namespace seedcal
