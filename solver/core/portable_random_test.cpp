// The portable draws (core/portable_random.hpp): golden values for a fixed seed, which every
// standard library must reproduce (std::mt19937_64's output is fixed by the C++ standard and the
// transforms are fixed here), and the moments of the normal draws.
#include <gtest/gtest.h>

#include <cmath>

#include "solver/core/portable_random.hpp"

namespace seedcal {
namespace {

TEST(PortableRandom, GoldenValuesForSeed42) {
  std::mt19937_64 r(42);
  // Integer arithmetic only: exact on any platform.
  EXPECT_EQ(uniform01(r), 0.75515553295453897);
  EXPECT_EQ(uniform01(r), 0.63903139385469743);
  EXPECT_EQ(uniform01(r), 0.7521452007480266);
  // The polar method uses log, which a C library may round differently in the last bit: 1e-15.
  std::mt19937_64 q(42);
  PortableNormal n(0.0, 1.0);
  for (double golden : {1.2938204232729367, 0.70498826642085988, 0.39797739618378869, -0.57409480672026136})
    EXPECT_NEAR(n(q), golden, 1e-15 * std::abs(golden));
}

TEST(PortableRandom, NormalMomentsAndUniformRange) {
  std::mt19937_64 r(7);
  PortableNormal n(2.0, 0.5);
  const int count = 100000;
  double sum = 0.0, sum2 = 0.0;
  for (int i = 0; i < count; ++i) {
    const double x = n(r);
    sum += x;
    sum2 += x * x;
  }
  const double mean = sum / count, sd = std::sqrt(sum2 / count - mean * mean);
  // Four standard errors: sd/sqrt(n) for the mean, sd/sqrt(2n) for the sd (a normal sample).
  EXPECT_NEAR(mean, 2.0, 4.0 * 0.5 / std::sqrt(count));
  EXPECT_NEAR(sd, 0.5, 4.0 * 0.5 / std::sqrt(2.0 * count));
  const PortableUniform u(-1.0, 3.0);
  for (int i = 0; i < 1000; ++i) {
    const double x = u(r);
    EXPECT_GE(x, -1.0);
    EXPECT_LT(x, 3.0);
  }
}

}  // namespace
}  // namespace seedcal
