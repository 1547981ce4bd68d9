#pragma once
// The `direct_shear` scene: a strain-controlled circular shear box (the ZJ apparatus of the paper:
// inner diameter 61.8 mm, sample 20 mm high split at mid-height).
//
// Rig (docs/scenes/direct_shear.md). `zj`, the default, is the apparatus as it is built: two steel
// rings of real wall thickness (walls/tube_shape.hpp) with flat annular faces at the split, a small
// gap between the faces, the lower ring on a floor, and a loading cap, a disc of the bore's
// diameter, that moves inside the upper ring. As the upper ring moves the faces cover the two
// crescents that open between the bores: seeds of the lower half cannot rise outside the upper
// ring, and seeds of the upper half do not hang over open space. `shells` keeps the older rig for
// comparison: zero-thickness cylindrical shells with open rims (walls/cylinder_shape.hpp) and an
// unbounded plane lid.
//
// Protocol: seeds are poured into the box (the upper ring continues as a guide above the sample so
// the pour stays inside), settled, and the specimen is formed: levelled (seeds whose centre lies
// above the sample height are removed) or weighed in to a bulk density (the lowest seeds up to the
// specimen's mass, as a lab weighs its specimen; ASTM D3080 sec. 8). A servo cap consolidates the
// specimen at the normal stress (default 200 kPa) until it settles, then the upper ring and the cap
// move horizontally at the shear speed for the shear displacement while the cap keeps the stress.
// The upper ring rests on its seat under its weight and lifts off when seeds wedged at the split
// push it up harder (as the ZJ box's upper half, on balls, does), or is held (`upper_ring_fixed`).
// Shear stress = the horizontal force the seeds exert on the upper ring and the cap / the nominal
// area pi D^2 / 4; shear strength = the peak of that curve after a moving average over
// `smoothing_m` (0.5 mm), searched up to `failure_displacement_m` (GB/T 50123, the standard of the
// ZJ apparatus: the peak, or the stress at 4 mm if none). Also reported: whether the curve peaked
// before that displacement, the stress ratio tau/sigma, the dilation (cap rise) curve, and the
// inertial number I = gamma_dot d sqrt(rho / sigma) with gamma_dot = v / d (a shear band about one
// seed thick), which should stay below 1e-3 for a quasi-static test.
#include <array>
#include <string>

#include "solver/scenes/run_plan.hpp"

namespace seedcal {

enum class ShearBoxGeometry {
  zj,      // thick rings with flat faces at the split, a gap, a loading cap inside the upper ring
  shells,  // zero-thickness shells with open rims and an unbounded plane lid (the older rig)
};
const char* to_string(ShearBoxGeometry g);

struct DirectShearSpec {
  PhysicsSpec physics;
  TimeStepSpec time_step;
  SeedSpec seeds;
  std::uint16_t box_material = 0;
  double diameter_m = 0.0618;
  double sample_height_m = 0.020;
  double normal_stress_pa = 2.0e5;
  double shear_speed_m_s = 0.01;
  double shear_displacement_m = 0.006;
  double pour_height_factor = 3.0;   // guide height above the sample, in sample heights
  ShearBoxGeometry geometry = ShearBoxGeometry::zj;
  // zj: the rings' wall thickness, wider than the shear displacement so the faces cover the
  // crescents (a ZJ ring's wall is about 10 mm), and the gap between their faces at the split,
  // below the smallest sphere diameter of the seeds so none passes through it.
  double ring_wall_thickness_m = 0.010;
  double ring_gap_m = 0.001;
  // > 0: the specimen is made to this bulk density (mass = density x pi D^2/4 x H, the lowest seeds
  // kept), as a lab specimen is weighed in (ASTM D3080 sec. 8); 0: seeds whose centre lies above
  // the sample height are removed.
  double sample_density_kg_m3 = 0.0;
  double consolidation_max_time_s = 0.3;
  double lid_max_speed_m_s = 0.1;
  double record_interval_s = 2e-4;
  double smoothing_m = 0.0005;       // moving-average window of the curve before the peak
  // Failure (GB/T 50123, the ZJ apparatus's standard): the peak of the smoothed curve up to this
  // shear displacement, or the stress there when the curve is still rising (ASTM D3080: 10 % of
  // the diameter).
  double failure_displacement_m = 0.004;
  // The upper ring rests on the lower one and lifts off it when the seeds push it up with more than
  // its weight (AS 1289.6.2.2 note 1: restraining the top half vertically "can significantly
  // influence the measured shear force"); fixed: it never moves vertically.
  bool upper_ring_fixed = false;
  double upper_ring_mass_kg = 0.5;
  int threads = 1;
  std::uint64_t seed = 0;
  FrameObserver observer;  // frames for a trajectory (optional)
};

struct ShearSample {
  double displacement_m, shear_stress_pa, normal_stress_pa, lid_height_m, smoothed_shear_stress_pa,
      upper_ring_lift_m;
};

struct DirectShearResult {
  RunReport run;
  double shear_strength_pa = 0.0;      // peak shear stress
  double displacement_at_peak_m = 0.0;
  double stress_ratio = 0.0;           // peak tau / mean sigma during shear
  double mean_normal_stress_pa = 0.0;
  double inertial_number = 0.0;
  double dilation_m = 0.0;             // cap rise from the start of shear to the end
  // The smoothed curve over the whole path: "peak" (it falls after its maximum by more than its
  // noise), "plateau" (it levels off), or "rising" (its maximum lies at the end of the path, so the
  // strength is the stress at the failure displacement of a curve still climbing).
  std::string curve_shape;
  double upper_ring_lift_m = 0.0;      // highest lift of the upper ring off the lower one
  // The specimen as consolidated, at the start of shear: the lid's height above the floor and the
  // seeds whose clump reaches across the split plane (z = H/2): what interlocks the two halves.
  double consolidated_height_m = 0.0;
  std::size_t seeds_across_split = 0;
  std::size_t seeds = 0;
  double sample_mass_kg = 0.0;
  std::vector<ShearSample> curve;
  std::vector<std::vector<std::pair<Vec3, double>>> spheres;  // final state, for the picture
  // The rig at the end of shear cut through its axis in the x-z plane, for the picture: each wall
  // of a ring and the cap as a rectangle {x_min, z_min, x_max, z_max} (m); a shell as a line
  // (x_min = x_max).
  std::vector<std::array<double, 4>> rig_outline_m;
};

DirectShearResult run_direct_shear(const DirectShearSpec& spec);
// What a run of `spec` will simulate (run_plan.hpp).
RunPlan plan_direct_shear(const DirectShearSpec& spec);

}  // namespace seedcal
