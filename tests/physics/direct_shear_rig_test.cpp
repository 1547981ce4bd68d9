// The ZJ shear box (solver/scenes/direct_shear.hpp, geometry zj): through the whole shear every
// seed stays in a ring's bore, the upper ring's above the split and the lower ring's below it, since
// the rings' faces cover the crescents that open between the bores (docs/scenes/direct_shear.md).
// Nine-sphere Jinong 1 seeds, Table 6 values, the quick rig's 4.5 mm of shear.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "solver/scenes/direct_shear.hpp"
#include "tests/support/cli.hpp"
#include "tests/support/worlds.hpp"

namespace seedcal {
namespace {

struct Excursion {
  DirectShearResult result;
  double worst_m = -1.0;    // largest distance of a sphere centre beyond its ring's bore radius
  double surface_m = -1.0;  // largest distance of a sphere's surface beyond it
  double overlap_m = 0.0;   // deepest contact overlap seen in those frames
  int frames = 0;        // frames checked during shear
};

Excursion shear(ShearBoxGeometry geometry) {
  DirectShearSpec spec;
  spec.physics.materials = {{"seed", 1340.0, 1.65e8, 0.4}, {"steel", 7850.0, 2.0e10, 0.3}};
  spec.physics.interactions = {{"seed_seed", 0, 0, 0.45, 0.55, 0.05}, {"seed_steel", 0, 1, 0.65, 0.4, 0.05}};
  spec.physics.contact.rolling = RollingModel::cdt;
  spec.physics.contact.cdt_lever_from_centre_of_mass = true;
  const auto spheres = testing::read_xyzr(testing::source_dir() + "/data/bench/clump9.txt");
  spec.seeds.body = clump_body(spheres, 1340.0, 0);
  spec.seeds.scale = {1.0, 0.1308, 1.0 - 2 * 0.1308, 1.0 + 2 * 0.1308};
  spec.box_material = 1;
  spec.geometry = geometry;
  spec.shear_speed_m_s = 0.02;
  spec.shear_displacement_m = 0.0045;
  spec.seed = 1;
  const double R = 0.5 * spec.diameter_m, split = 0.5 * spec.sample_height_m;
  Excursion ex;
  spec.observer.interval_s = 0.005;
  spec.observer.on_frame = [&](const Simulation& sim) {
    const auto upper = std::find_if(sim.walls().begin(), sim.walls().end(),
                                    [](const Wall& w) { return w.name == "upper_ring"; });
    const bool shearing = std::any_of(sim.walls().begin(), sim.walls().end(),
                                      [](const Wall& w) { return w.name == "lid"; }) &&
                          upper->pose.origin_m.x() > 0.0;
    if (!shearing) return;
    ++ex.frames;
    const double ux = upper->pose.origin_m.x();
    ex.overlap_m = std::max(ex.overlap_m, sim.stats().max_overlap_m);
    for (std::size_t i = 0; i < sim.spheres().size(); ++i) {
      const Vec3& c = sim.spheres().position_m[i];
      const double axis_x = c.z() > split ? ux : 0.0;
      const double beyond = std::hypot(c.x() - axis_x, c.y()) - R;
      ex.worst_m = std::max(ex.worst_m, beyond);
      // The part of the sphere on the same side of the split as its centre.
      ex.surface_m = std::max(ex.surface_m, beyond + sim.spheres().radius_m[i]);
    }
  };
  ex.result = run_direct_shear(spec);
  return ex;
}

TEST(DirectShearRig, ZjRingsKeepEverySeedInItsBoreThroughShear) {
  const Excursion zj = shear(ShearBoxGeometry::zj);
  ASSERT_EQ(zj.result.run.failure.status, RunStatus::ok) << zj.result.run.failure.message;
  std::printf("zj: %d frames, largest centre excursion beyond the bore %.3f mm, surface %.3f mm, deepest overlap %.3f mm, strength %.1f kPa (%s)\n",
              zj.frames, 1e3 * zj.worst_m, 1e3 * zj.surface_m, 1e3 * zj.overlap_m, zj.result.shear_strength_pa / 1e3, zj.result.curve_shape.c_str());
  // Frames every 5 ms over 4.5 mm at 20 mm/s: about 45.
  EXPECT_GT(zj.frames, 30);
  // A centre at the bore's radius would mean a sphere half inside the steel: every centre stays
  // inside (the smallest sphere, 1.75 mm x 0.74, keeps its centre 1.3 mm in at rest, less its
  // overlap with the steel, a few micrometres).
  EXPECT_LT(zj.worst_m, 0.0);
  // No sphere reaches further into the steel than the deepest contact overlap of the run.
  EXPECT_LE(zj.surface_m, zj.overlap_m);
}

}  // namespace
}  // namespace seedcal
