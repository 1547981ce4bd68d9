#pragma once
// Reading a direct shear's stress-displacement curve, as the apparatus's standard reads it
// (GB/T 50123, the ZJ strain-controlled box): the curve smoothed over a window of displacement,
// its failure (the peak, or the stress at the failure displacement when it has not peaked by
// then), and its shape over the whole path.
#include <string>
#include <vector>

#include "solver/scenes/direct_shear.hpp"

namespace seedcal {

// Fills each sample's smoothed_shear_stress_pa: the mean of the stresses within window_m / 2 of
// its displacement (a centred moving average).
void smooth_curve(std::vector<ShearSample>& curve, double window_m);

struct ShearFailure {
  double shear_strength_pa = 0.0;  // the largest smoothed stress up to the failure displacement
  double displacement_m = 0.0;     // where it is
};
// GB/T 50123: the peak of the smoothed curve up to `failure_displacement_m`; for a curve still
// rising there, that is the stress at the failure displacement. 0 for an empty curve.
ShearFailure read_failure(const std::vector<ShearSample>& curve, double failure_displacement_m);

// "rising", "peak" or "plateau" (DirectShearResult::curve_shape).
std::string curve_shape(const std::vector<ShearSample>& curve, double window_m);

}  // namespace seedcal
