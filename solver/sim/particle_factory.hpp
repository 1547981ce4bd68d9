#pragma once
// The particle factory: inserts copies of a body template at random non-overlapping poses inside a
// region, each scaled by a factor drawn from a truncated normal distribution (the paper generates
// seeds "by a normal distribution in terms of volume" from the measured width distribution), until
// a count or a total mass is reached. Deterministic for the simulation's seed.
#include <cstdint>
#include <string>

#include "solver/sim/simulation.hpp"

namespace seedcal {

struct InsertionRegion {
  enum class Kind { box, cylinder } kind = Kind::box;
  Vec3 lo_m = Vec3::Zero(), hi_m = Vec3::Zero();  // box (axis-aligned, world)
  Vec3 base_m = Vec3::Zero();                     // cylinder: centre of its bottom disc, axis +z
  double radius_m = 0.0, height_m = 0.0;
};

// Normal(mean, sd) truncated to [lo, hi] by rejection; sd = 0 gives the mean.
struct ScaleDistribution {
  double mean = 1.0, sd = 0.0, lo = 1.0, hi = 1.0;
};

struct FactorySpec {
  BodyDef body;                     // template: spheres in the principal frame, mass properties
  InsertionRegion region;
  ScaleDistribution scale;
  std::size_t count = 0;            // stop after this many (0: no count limit)
  double total_mass_kg = 0.0;       // stop when this mass is placed (0: no mass limit)
  bool random_orientation = true;
  Vec3 velocity_m_s = Vec3::Zero();
  std::uint64_t max_attempts = 0;   // 0: 1000 per body asked for (or 1e6 with a mass limit)
};

struct FactoryResult {
  std::size_t placed = 0;
  double mass_kg = 0.0;
  bool complete = false;
  std::string stop_reason;
};

// The template scaled by s: offsets and radii x s, mass x s^3, inertia x s^5.
BodyDef scaled_body(const BodyDef& body, double s);

FactoryResult insert_particles(Simulation& sim, const FactorySpec& spec);

}  // namespace seedcal
