#pragma once
// Uniform draws that are the same on every standard library: std::mt19937_64's output is fixed by
// the C++ standard, std::uniform_real_distribution's algorithm is not (libstdc++, libc++ and MSVC
// differ), so the designs, the GP's starts and the posterior's samples use this transform.
#include <cstdint>
#include <random>

namespace seedcal {

// Uniform on [0, 1): the top 53 bits of one 64-bit output, times 2^-53.
inline double unit_uniform(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

}  // namespace seedcal
