// The EPSD rolling slot (rolling_epsd.hpp) on one contact: the spring's moment and damping while
// elastic, the plastic limit without damping, no resistance to twisting, the spring turning with
// the contact; four lanes against one.
#include "solver/contact/rolling_epsd.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "solver/contact/lanes_test_support.hpp"

namespace seedcal::lanes {
namespace {

using testing::norm;

constexpr double kSn = 2.4e5, kFn = 10.0, kRStar = 2.175e-3, kInertia = 1.2e-9, kDt = 5e-6,
                 kEta = 0.3, kMu = 0.05;

EpsdIn<double> contact(const V3<double>& spin, double mu = kMu) {
  return {{0.0, 0.0, 1.0}, spin, spin, mu, kFn, kSn, kRStar, kInertia};
}

double rolling_stiffness() { return 2.25 * kSn * kMu * kMu * kRStar * kRStar; }  // eq. 13

TEST(RollingEpsd, ElasticSpringAndDamping) {
  const V3<double> spin{2.0, 0.0, 0.0};  // rad/s, rolling about x
  V3<double> m_k{0.0, 0.0, 0.0};
  const V3<double> tau = epsd_torque<ScalarOps>(contact(spin), kEta, kDt, m_k);
  const double kr = rolling_stiffness();
  const double cr = kEta * 2.0 * std::sqrt(kInertia * kr);  // eq. 17
  EXPECT_NEAR(m_k.x, -kr * 2.0 * kDt, 1e-15 * kr * 2.0 * kDt);  // eq. 11
  EXPECT_NEAR(tau.x, -kr * 2.0 * kDt - cr * 2.0, 1e-14 * std::abs(tau.x));
  EXPECT_EQ(tau.y, 0.0);
  EXPECT_EQ(tau.z, 0.0);
}

TEST(RollingEpsd, TwistingIsNotResisted) {
  V3<double> m_k{0.0, 0.0, 0.0};
  const V3<double> tau = epsd_torque<ScalarOps>(contact({0.0, 0.0, 50.0}), kEta, kDt, m_k);
  EXPECT_EQ(norm(tau), 0.0);
  EXPECT_EQ(norm(m_k), 0.0);
}

TEST(RollingEpsd, PlasticLimitWithoutDamping) {
  const double m_max = kMu * kRStar * kFn;  // eq. 12
  V3<double> m_k{-0.99 * m_max, 0.0, 0.0};
  const V3<double> tau = epsd_torque<ScalarOps>(contact({1e4, 0.0, 0.0}), kEta, kDt, m_k);
  EXPECT_NEAR(norm(m_k), m_max, 1e-15 * m_max);
  EXPECT_NEAR(tau.x, -m_max, 1e-15 * m_max);  // the spring alone, at the limit
}

TEST(RollingEpsd, SpringTurnsWithTheContactKeepingItsMagnitude) {
  EpsdIn<double> in = contact({0.0, 0.0, 0.0});
  in.normal = {std::sin(0.2), 0.0, std::cos(0.2)};
  V3<double> m_k{1e-6, 2e-6, 0.0};
  const double len0 = norm(m_k);
  epsd_torque<ScalarOps>(in, kEta, kDt, m_k);
  // To a few roundings of the projection and the rescaling: 4 machine epsilons of the moment.
  const double eps = 4.0 * std::numeric_limits<double>::epsilon() * len0;
  EXPECT_NEAR(dot(m_k, in.normal), 0.0, eps);
  EXPECT_NEAR(norm(m_k), len0, eps);
}

TEST(RollingEpsd, NoRollingFrictionNoSpring) {
  V3<double> m_k{1e-6, 0.0, 0.0};
  const V3<double> tau = epsd_torque<ScalarOps>(contact({2.0, 0.0, 0.0}, 0.0), kEta, kDt, m_k);
  EXPECT_EQ(norm(tau), 0.0);
  EXPECT_EQ(norm(m_k), 0.0);
}

TEST(RollingEpsd, FourLanesGiveTheBitsOfOne) {
  using testing::G4;
  using testing::Generic4Ops;
  // Elastic, twisting, plastic, turned.
  const V3<double> spin[4] = {{2, 0, 0}, {0, 0, 50}, {1e4, 0, 0}, {0.1, -0.3, 0}};
  const V3<double> n[4] = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {std::sin(0.2), 0, std::cos(0.2)}};
  const V3<double> m0[4] = {{0, 0, 0}, {0, 0, 0}, {-1e-6, 0, 0}, {1e-6, 2e-6, 0}};
  EpsdIn<G4> in4{testing::lanes4(n[0], n[1], n[2], n[3]),
                 testing::lanes4(spin[0], spin[1], spin[2], spin[3]),
                 testing::lanes4(spin[0], spin[1], spin[2], spin[3]),
                 Generic4Ops::splat(kMu),
                 Generic4Ops::splat(kFn),
                 Generic4Ops::splat(kSn),
                 Generic4Ops::splat(kRStar),
                 Generic4Ops::splat(kInertia)};
  V3<G4> m4 = testing::lanes4(m0[0], m0[1], m0[2], m0[3]);
  const V3<G4> tau4 = epsd_torque<Generic4Ops>(in4, kEta, kDt, m4);
  for (int l = 0; l < 4; ++l) {
    EpsdIn<double> in = contact(spin[l]);
    in.normal = n[l];
    V3<double> m = m0[l];
    const V3<double> tau = epsd_torque<ScalarOps>(in, kEta, kDt, m);
    EXPECT_TRUE(testing::same_bits(testing::lane(tau4, l), tau)) << l;
    EXPECT_TRUE(testing::same_bits(testing::lane(m4, l), m)) << l;
  }
}

}  // namespace
}  // namespace seedcal::lanes
