// The overlap guard (sim/guards.hpp, sim/overlap_limits.hpp): a lone sphere may overlap half its
// radius; a clump's sphere, a piece of the seed's surface, half the seed's volume-equivalent
// radius and at most twice its own (where the contact point reaches its centre). Checked against
// Hertz's static overlap under a known load, delta = (3 F / (4 E* sqrt(R*)))^(2/3) (Johnson,
// Contact Mechanics, 1985, eq. 4.23): a small sphere at a clump's tip carrying the body's weight at
// 1.2 of its radius runs on and reports it; a lone sphere with the same load stops at half its
// radius; a tip standing clear of its clump loaded past twice its radius stops.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "solver/sim/overlap_limits.hpp"
#include "tests/support/worlds.hpp"

namespace seedcal {
namespace {

constexpr double kBig = 0.004, kTip = 0.0005;  // the clump's central and tip sphere radii, m
// How far the tip stands out of the central sphere: within the tip's diameter (the two overlap, as
// in a fill), or beyond it (a tip on its own, which can be buried past its limit before the
// central sphere touches).
constexpr double kStandOut = 0.0008, kStandClear = 0.0013;

testing::MaterialSpec seed() {
  testing::MaterialSpec m = testing::table6_seed();
  m.restitution = 0.1;  // a heavily damped contact: at rest within a few periods
  m.static_friction = 0.0;
  return m;
}

// E* of the seed on the plane (steel, 2e11 Pa, nu 0.3) and of two seeds.
double e_star_wall(const testing::MaterialSpec& m) {
  return 1.0 / ((1.0 - m.poisson_ratio * m.poisson_ratio) / m.youngs_modulus_pa + (1.0 - 0.09) / 2e11);
}

// Hertz's load for an overlap `delta` on a contact of reduced radius r_star and modulus e_star.
double hertz_load_n(double delta, double r_star, double e_star) {
  return 4.0 / 3.0 * e_star * std::sqrt(r_star) * std::pow(delta, 1.5);
}

// The clump: a central sphere and a small tip sphere standing `stand_out` out of it, the tip
// pointing down (-z) and just touching z = `tip_bottom_m`.
BodyDef tipped_clump(const testing::MaterialSpec& m, double tip_bottom_m, double stand_out = kStandOut) {
  BodyDef b = clump_body({{Vec3::Zero(), kBig}, {Vec3(0, 0, -(kBig + stand_out - kTip)), kTip}},
                         m.density_kg_m3, 0);
  std::size_t tip = 0;
  for (std::size_t i = 0; i < b.spheres.size(); ++i)
    if (b.spheres[i].radius_m < b.spheres[tip].radius_m) tip = i;
  const Vec3 o = b.spheres[tip].offset_m;
  b.orientation = Quat::FromTwoVectors(o, -Vec3::UnitZ());
  b.position_m = Vec3(0, 0, tip_bottom_m + kTip + o.norm());
  return b;
}

// A clump standing on three such tips, 120 degrees apart about its axis (a tripod stands where one
// tip would topple; its tips stand clear of the central sphere, as legs): each carries a third of
// its weight.
BodyDef tripod_clump(const testing::MaterialSpec& m, double tip_bottom_m) {
  constexpr double kSpread = 0.002;  // the tips' distance from the axis, m
  const double h = kBig + kStandOut - kTip;
  std::vector<SphereXYZR> spheres = {{Vec3::Zero(), kBig}};
  for (int k = 0; k < 3; ++k) {
    const double a = 2.0 * std::numbers::pi * k / 3.0;
    spheres.push_back({Vec3(kSpread * std::cos(a), kSpread * std::sin(a), -h), kTip});
  }
  BodyDef b = clump_body(spheres, m.density_kg_m3, 0);
  Vec3 axis = Vec3::Zero();
  for (const SphereDef& sd : b.spheres)
    if (sd.radius_m == kTip) axis += sd.offset_m;
  b.orientation = Quat::FromTwoVectors(axis, -Vec3::UnitZ());
  double lowest = 0.0;
  for (const SphereDef& sd : b.spheres) lowest = std::min(lowest, (b.orientation * sd.offset_m).z() - sd.radius_m);
  b.position_m = Vec3(0, 0, tip_bottom_m - lowest);
  return b;
}

struct Outcome {
  RunStatus status = RunStatus::ok;
  std::string message;
  double overlap_m = 0.0, deepest_fraction = 0.0;
};

// `body` pressed on the plane z = 0 by its weight under gravity g, from rest just touching it;
// 6 ms, about twenty periods of the contact.
Outcome press_on_plane(const BodyDef& body, double g) {
  const testing::MaterialSpec m = seed();
  SimulationOptions opt;
  opt.gravity_m_s2 = Vec3(0, 0, -g);
  Simulation sim = testing::body_on_plane(testing::make_table(m, 2e11, 0.3), opt, body);
  const bool ok = sim.run(static_cast<std::uint64_t>(0.006 / sim.options().dt_s));
  return {ok ? RunStatus::ok : sim.failure().status, sim.failure().message, sim.stats().max_overlap_m,
          sim.deepest_overlap_fraction()};
}

TEST(OverlapLimits, LoneSphereHalfItsRadiusClumpSphereHalfTheSeeds) {
  const testing::MaterialSpec m = seed();
  SimulationOptions opt;
  opt.dt_s = 1e-7;
  Simulation sim(testing::make_table(m), opt);
  sim.add_body(sphere_body(0.002, m.density_kg_m3, 0));
  BodyDef clump = tipped_clump(m, 0.01);
  sim.add_body(clump);
  // A clump declared lighter than its largest sphere: that sphere is its reference radius.
  BodyDef light = clump;
  light.position_m.x() += 0.02;
  light.mass_kg = 1e-9;
  sim.add_body(light);
  ASSERT_TRUE(sim.run(1));
  const GuardOptions g;
  const std::vector<double> limit =
      sphere_overlap_limits(sim.bodies(), sim.spheres(), {{"particle", m.density_kg_m3, 1e8, 0.4}}, g);
  const double r_eq = std::cbrt(3.0 * clump.mass_kg / (4.0 * std::numbers::pi * m.density_kg_m3));
  ASSERT_GT(r_eq, kBig);  // the union is more than the central sphere
  for (std::size_t i = 0; i < limit.size(); ++i) {
    const double r = sim.spheres().radius_m[i];
    const std::uint32_t b = sim.spheres().body[i];
    const bool lone = sim.bodies().first_sphere[b + 1] - sim.bodies().first_sphere[b] == 1;
    const bool light_body = sim.bodies().mass_kg[b] < 1e-6;
    double expect = 0.5 * r;
    if (!lone) expect = std::min(2.0 * r, 0.5 * (light_body ? kBig : r_eq));
    EXPECT_DOUBLE_EQ(limit[i], expect) << "sphere " << i << " r " << r;
    EXPECT_GE(limit[i], overlap_prefilter_fraction(g) * r);
  }
  // The central sphere of the clump: half the volume-equivalent radius, not its own radius.
  EXPECT_NEAR(*std::max_element(limit.begin(), limit.end()), 0.5 * r_eq, 1e-15);
}

// Three tips carry the clump at 1.2 of their radius: past Hertz's small-overlap range, within the
// clump sphere's limit (the central sphere still clear of the plane). The run goes on, rests at
// Hertz's overlap and reports how deep it went.
TEST(OverlapGuard, ClumpTipCarriesHertzOverlapPastItsRadius) {
  const testing::MaterialSpec m = seed();
  const double delta = 1.2 * kTip;
  ASSERT_LT(delta, kStandOut);
  const BodyDef b = tripod_clump(m, 0.0);
  const double g = 3.0 * hertz_load_n(delta, kTip, e_star_wall(m)) / b.mass_kg;
  const Outcome o = press_on_plane(b, g);
  ASSERT_EQ(o.status, RunStatus::ok) << o.message;
  // At rest the contact carries the weight exactly; 1e-4: the residue of about twenty damped
  // periods (restitution 0.1).
  EXPECT_NEAR(o.overlap_m / delta, 1.0, 1e-4);
  EXPECT_GE(o.deepest_fraction, 1.2 * (1.0 - 1e-4));
  EXPECT_LT(o.deepest_fraction, 2.0);
}

// A lone sphere of the tip's radius and the clump's mass, loaded to a Hertz overlap of 0.6 of its
// radius: past half its radius, the run stops and says so.
TEST(OverlapGuard, LoneSphereWithTheSameLoadStops) {
  const testing::MaterialSpec m = seed();
  const double delta = 0.6 * kTip;
  const BodyDef clump = tipped_clump(m, 0.0);
  BodyDef lone = sphere_body(kTip, m.density_kg_m3, 0);
  lone.mass_kg = clump.mass_kg;
  lone.principal_inertia_kg_m2 = Vec3::Constant(0.4 * clump.mass_kg * kTip * kTip);
  lone.position_m = Vec3(0, 0, kTip);
  const double g = hertz_load_n(delta, kTip, e_star_wall(m)) / lone.mass_kg;
  const Outcome o = press_on_plane(lone, g);
  EXPECT_EQ(o.status, RunStatus::deep_overlap);
  EXPECT_NE(o.message.find("limit 0.00025 m"), std::string::npos) << o.message;
}

// A tip standing clear of its clump, loaded to 2.2 of its radius (the central sphere still clear
// of the plane): the contact point would pass the tip's centre; the run stops.
TEST(OverlapGuard, ClumpTipPastTwiceItsRadiusStops) {
  const testing::MaterialSpec m = seed();
  ASSERT_LT(2.2 * kTip, kStandClear);
  const BodyDef b = tipped_clump(m, 0.0, kStandClear);
  const double g = hertz_load_n(2.2 * kTip, kTip, e_star_wall(m)) / b.mass_kg;
  const Outcome o = press_on_plane(b, g);
  EXPECT_EQ(o.status, RunStatus::deep_overlap);
  EXPECT_NE(o.message.find("limit 0.001 m"), std::string::npos) << o.message;
}

// Sphere on sphere (the batch kernel's path): the clump's tip lands on a heavy lone sphere resting
// on the plane and is loaded to 1.2 of its radius (R* = r_tip r / (r_tip + r)); its first
// compression reaches at least that overlap (no more than (5/2)^(2/3) of it, the undamped
// overshoot of a load applied at rest) and the run goes on. (The clump balanced on a ball tips
// over afterwards: only the first compression is read.)
TEST(OverlapGuard, ClumpTipOnALoneSphere) {
  const testing::MaterialSpec m = seed();
  const double delta = 1.2 * kTip;
  const double r_star = kTip * kBig / (kTip + kBig);
  const double e_star = 0.5 * m.youngs_modulus_pa / (1.0 - m.poisson_ratio * m.poisson_ratio);
  BodyDef ball = sphere_body(kBig, m.density_kg_m3, 0);
  ball.position_m = Vec3(0, 0, kBig);
  BodyDef clump = tipped_clump(m, 2.0 * kBig);
  const double g = hertz_load_n(delta, r_star, e_star) / clump.mass_kg;
  SimulationOptions opt;
  opt.gravity_m_s2 = Vec3(0, 0, -g);
  Simulation sim = testing::body_on_plane(testing::make_table(m, 2e11, 0.3), opt, ball);
  sim.add_body(clump);
  ASSERT_TRUE(sim.run(static_cast<std::uint64_t>(0.002 / sim.options().dt_s))) << sim.failure().message;
  EXPECT_GE(sim.deepest_overlap_fraction(), 1.2);
  EXPECT_LE(sim.deepest_overlap_fraction(), 1.2 * std::pow(2.5, 2.0 / 3.0));
}

}  // namespace
}  // namespace seedcal
