#pragma once
// Random draws that are the same on every standard library. std::mt19937_64's output is fixed by
// the C++ standard, but std::uniform_real_distribution and std::normal_distribution are not: their
// algorithms differ between libstdc++, libc++ and MSVC, so a seed would give other seeds, other
// packings and other results elsewhere. These transforms of the engine's integers are fixed here.
#include <cmath>
#include <cstdint>
#include <random>

namespace seedcal {

// Uniform on [0, 1): the top 53 bits of one 64-bit output, times 2^-53 (every double of the form
// k 2^-53, each with probability 2^-53).
inline double uniform01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

// Uniform on [a, b), as std::uniform_real_distribution<double>(a, b) but portable.
class PortableUniform {
 public:
  PortableUniform(double a, double b) : a_(a), b_(b) {}
  double operator()(std::mt19937_64& rng) const { return a_ + (b_ - a_) * uniform01(rng); }

 private:
  double a_, b_;
};

// Normal with mean and sd, by Marsaglia's polar method (Marsaglia & Bray 1964, SIAM Rev. 6, 260):
// points uniform in the square [-1, 1)^2 are kept inside the unit disc (s in (0, 1)), and each kept
// point gives two independent standard normals u sqrt(-2 ln s / s), v sqrt(-2 ln s / s). Only
// sqrt (correctly rounded) and log are used; the second value is kept for the next call.
class PortableNormal {
 public:
  PortableNormal(double mean, double sd) : mean_(mean), sd_(sd) {}
  double operator()(std::mt19937_64& rng) {
    if (has_spare_) {
      has_spare_ = false;
      return mean_ + sd_ * spare_;
    }
    double u, v, s;
    do {
      u = 2.0 * uniform01(rng) - 1.0;
      v = 2.0 * uniform01(rng) - 1.0;
      s = u * u + v * v;
    } while (s >= 1.0 || s == 0.0);
    const double f = std::sqrt(-2.0 * std::log(s) / s);
    spare_ = v * f;
    has_spare_ = true;
    return mean_ + sd_ * u * f;
  }

 private:
  double mean_, sd_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace seedcal
