#pragma once
// Filling a target shape with spheres: automatic (a distance-field fill with a smoothness control
// like the commercial one, or a sphere-count target) and manual (N spheres along the principal
// axes, one of them the hilum, placed by an optimiser that maximises the intersection over union
// with the shape). Spheres come back in the shape's frame. Both are deterministic: the same
// inputs give the same spheres bit for bit on any thread count. See docs/clumps.md.
#include <string>
#include <vector>

#include "calibrate/clumps/seed_shape.hpp"

namespace seedcal {

struct AutoFillOptions {
  // Exactly one of: smoothness in [0, 5] (0 finest), or a sphere-count target (> 0).
  double smoothness = -1.0;
  int target_spheres = 0;
  int voxels = 200;  // voxels along the shape's longest side
  double protrusion = 0.3;  // radius = depth + protrusion * r_min (see auto_fill.cpp)
  // A floor under r_min, m (0: none): no sphere smaller than this, whatever the smoothness or the
  // count asks. A clump's smallest sphere carries a contact's whole force alone, and Hertz contact
  // holds only while its overlap stays well below its radius (docs/clumps.md, "Smallest sphere").
  double min_radius_floor_m = 0.0;
};

struct AutoFillResult {
  std::vector<SphereXYZR> spheres;
  double min_radius_m = 0.0;  // the fill's smallest allowed radius (what smoothness sets)
  double voxel_m = 0.0;
};

// Smallest sphere radius for a smoothness, relative to the shape's volume-equivalent radius:
// r_min = r_eq * 0.0223 * 2.05^s (fitted so a Jinong-1-sized ellipsoid gets about 1,800 spheres at
// s = 0 and about 180 at s = 2, as the commercial code's counts in the paper's Table 4).
double smoothness_min_radius(const Shape& shape, double smoothness);

// Throws std::invalid_argument for options out of range.
AutoFillResult auto_fill(const Shape& shape, const AutoFillOptions& options);

struct ManualFillOptions {
  int spheres = 9;               // odd, 5..15
  int max_evaluations = 20000;   // of the optimiser, over all its restarts
  int grid = 48;                 // lines per axis of the IoU objective during optimisation
  // Every sphere reaches out of every other sphere by at least this fraction of its radius, so
  // that none is buried (solver/clump/buried_spheres.hpp tolerates 1 %; the margin keeps the
  // fill clear of that line).
  double min_protrusion = 0.05;
  // Smallest sphere radius, over the shape's smallest semi-axis. The stable time step follows the
  // smallest sphere (its Rayleigh step is proportional to the radius): measured on the nine
  // shipped models (docs/clumps.md), 0.4 costs at most 0.0015 of IoU against 0.25 and gives a
  // step 1.6 times longer.
  double min_radius_fraction = 0.4;
};

struct ManualFillResult {
  std::vector<SphereXYZR> spheres;  // [0] centre, [1] hilum (+x end), [2] tail (-x), then pairs
  double iou_objective = 0.0;       // on the optimisation grid
  int evaluations = 0;
  std::string layout;               // e.g. "x: 3, y pairs: 2, z pairs: 1"
};

// Needs an EllipsoidShape-like frame: x the length (hilum) axis; works on any shape whose
// principal axes are the coordinate axes and that is mirror-symmetric in y and z.
ManualFillResult manual_fill(const Shape& shape, const ManualFillOptions& options);

}  // namespace seedcal
