// The composed contact law (contact_law.hpp) on one contact: the slots added up as Hertz-Mindlin
// says, the force's torque about each body's centre, and the rolling slot each model selects.
#include "solver/contact/contact_law.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "solver/contact/lanes_test_support.hpp"
#include "solver/core/materials.hpp"

namespace seedcal::lanes {
namespace {

const ContactLaw<double> kLaw{1.65e8 / (2.0 * (1.0 - 0.16)), damping_beta(0.45), 0.55, 0.05,
                              std::sqrt(4.0 * (1.0 - 0.4) / (2.0 - 0.4))};

ContactKinematics<double> kinematics() {
  // Approaching at 0.1 m/s, sliding along x at 0.01 m/s, 20 um of overlap.
  return {{0.0, 0.0, 1.0}, 2e-5, 2.175e-3, 2.9e-4, {0.01, 0.0, 0.1}, {0.01, 0.0, 0.1}, 1.0};
}

ContactRotation<double, 2> rotation() {
  ContactRotation<double, 2> r;
  r.arm_i_m = {0.0, 0.0, 4.3e-3};
  r.arm_j_m = {1e-3, 0.0, -4.3e-3};
  r.cdt_lever_i_m = 4.3e-3;
  r.cdt_lever_j_m = 5.1e-3;
  r.relative_spin = {0.0, 3.0, 0.0};
  r.relative_spin_end = {0.0, 3.0, 0.0};
  r.rolling_inertia_kg_m2 = 1.2e-9;
  return r;
}

const ContactSettings kSettings{5e-6, false, 0.3};

TEST(ContactLaw, HertzMindlinIsTheSumOfItsSlots) {
  const ContactKinematics<double> k = kinematics();
  V3<double> t{0.0, 0.0, 0.0};
  const HertzMindlinForce<double> f = hertz_mindlin<ScalarOps>(kLaw, k, t, kSettings);
  const HertzNormal<double> el = hertz_normal<ScalarOps>(kLaw.e_star_pa, k.r_star_m, k.overlap_m);
  const double cn = normal_dashpot<ScalarOps>(kLaw.beta, 1.0, el.stiffness_n_m, k.m_star_kg);
  const double fn = el.force_n + cn * 0.1;  // elastic plus damping, repulsive
  EXPECT_DOUBLE_EQ(f.normal_force_n, fn);
  EXPECT_DOUBLE_EQ(f.normal_stiffness_n_m, el.stiffness_n_m);
  // The normal force pushes i away from j (-n); the tangential force opposes the slip (-x).
  EXPECT_DOUBLE_EQ(f.force_on_i_n.z, -fn);
  const double st = el.stiffness_n_m * kLaw.sqrt_tangential_ratio * kLaw.sqrt_tangential_ratio;
  const double ct = cn * kLaw.sqrt_tangential_ratio;
  EXPECT_DOUBLE_EQ(f.force_on_i_n.x, -st * 0.01 * kSettings.dt_s - ct * 0.01);
  EXPECT_DOUBLE_EQ(t.x, 0.01 * kSettings.dt_s);
}

TEST(ContactLaw, TorquesAndRollingModels) {
  const ContactKinematics<double> k = kinematics();
  const ContactRotation<double, 2> rot = rotation();
  V3<double> t{0.0, 0.0, 0.0}, m_k{0.0, 0.0, 0.0};
  const auto none = contact_law<ScalarOps, RollingModel::none, 2>(kLaw, k, rot, t, m_k, kSettings);
  EXPECT_TRUE(testing::same_bits(none.torque_i_n_m, cross(rot.arm_i_m, none.force_on_i_n)));
  EXPECT_TRUE(testing::same_bits(none.torque_j_n_m, cross(rot.arm_j_m, none.force_on_i_n)));
  EXPECT_EQ(none.roll_capacity_i_n_m, 0.0);
  EXPECT_EQ(none.roll_capacity_j_n_m, 0.0);
  EXPECT_EQ(testing::norm(none.rolling_torque_n_m), 0.0);

  t = {0.0, 0.0, 0.0};
  const auto cdt = contact_law<ScalarOps, RollingModel::cdt, 2>(kLaw, k, rot, t, m_k, kSettings);
  EXPECT_DOUBLE_EQ(cdt.roll_capacity_i_n_m,
                   kLaw.rolling_friction * std::abs(cdt.normal_force_n) * rot.cdt_lever_i_m);
  EXPECT_DOUBLE_EQ(cdt.roll_capacity_j_n_m,
                   kLaw.rolling_friction * std::abs(cdt.normal_force_n) * rot.cdt_lever_j_m);
  EXPECT_EQ(testing::norm(cdt.rolling_torque_n_m), 0.0);
  EXPECT_EQ(testing::norm(m_k), 0.0);  // CDT keeps no rolling spring

  t = {0.0, 0.0, 0.0};
  const auto epsd = contact_law<ScalarOps, RollingModel::epsd, 2>(kLaw, k, rot, t, m_k, kSettings);
  EXPECT_LT(epsd.rolling_torque_n_m.y, 0.0);  // opposes the relative rolling about y
  EXPECT_LT(m_k.y, 0.0);
  EXPECT_EQ(epsd.roll_capacity_i_n_m, 0.0);
}

}  // namespace
}  // namespace seedcal::lanes
