#pragma once
// Uniformly distributed random rotation (Shoemake, "Uniform random rotations", Graphics Gems III,
// 1992) from three portable uniforms (core/portable_random.hpp): the same rotation for a seed on
// any standard library.
#include <cmath>
#include <numbers>
#include <random>

#include "solver/core/portable_random.hpp"
#include "solver/core/vec.hpp"

namespace seedcal {

inline Quat uniform_random_rotation(std::mt19937_64& rng) {
  const double u1 = uniform01(rng), u2 = uniform01(rng), u3 = uniform01(rng);
  const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
  const double t2 = 2.0 * std::numbers::pi * u2, t3 = 2.0 * std::numbers::pi * u3;
  return Quat(b * std::cos(t3), a * std::sin(t2), a * std::cos(t2), b * std::sin(t3)).normalized();
}

}  // namespace seedcal
