#include "solver/scenes/shear_curve.hpp"

#include <algorithm>
#include <cmath>

namespace seedcal {

// Smooths the curve by a centred moving average over `window_m` of displacement: the instantaneous
// wall force of a coarse sample carries contact-scale spikes that the lab's load cell and its
// reading rate average out. The ring moves one way, so the samples are sorted by displacement and
// each window is a range [lo, hi) that only moves forward (linear in the samples); the window's
// samples are summed in order.
void smooth_curve(std::vector<ShearSample>& curve, double window_m) {
  const auto within = [&](std::size_t m, std::size_t k) {
    return std::abs(curve[m].displacement_m - curve[k].displacement_m) <= 0.5 * window_m;
  };
  const bool sorted = std::is_sorted(curve.begin(), curve.end(), [](const ShearSample& a, const ShearSample& b) {
    return a.displacement_m < b.displacement_m;
  });
  std::size_t lo = 0, hi = 0;
  for (std::size_t k = 0; k < curve.size(); ++k) {
    if (sorted) {
      while (!within(lo, k)) ++lo;
      if (hi < k + 1) hi = k + 1;
      while (hi < curve.size() && within(hi, k)) ++hi;
    } else {
      lo = 0;
      hi = curve.size();
    }
    double sum = 0.0;
    int n_avg = 0;
    for (std::size_t m = lo; m < hi; ++m)
      if (within(m, k)) {
        sum += curve[m].shear_stress_pa;
        ++n_avg;
      }
    curve[k].smoothed_shear_stress_pa = sum / n_avg;
  }
}

// The shape of the smoothed curve over the whole path (DirectShearResult::curve_shape). Its noise
// is the scatter of the smoothed stress between points one window apart (sd of the differences
// over sqrt 2: a plateau's scatter, plus the trend over one window where the curve moves). "rising":
// the maximum lies within the last window of the path. "peak": after the maximum the stress over
// the last window averages more than twice the noise below it. Otherwise "plateau".
std::string curve_shape(const std::vector<ShearSample>& curve, double window_m) {
  if (curve.size() < 3) return "rising";
  const double end = curve.back().displacement_m;
  std::size_t imax = 0;
  for (std::size_t k = 0; k < curve.size(); ++k)
    if (curve[k].smoothed_shear_stress_pa > curve[imax].smoothed_shear_stress_pa) imax = k;
  if (curve[imax].displacement_m >= end - window_m) return "rising";
  double ss = 0.0, tail = 0.0;
  std::size_t nd = 0, nt = 0;
  for (std::size_t k = 0, j = 0; k < curve.size(); ++k) {
    while (j < curve.size() && curve[j].displacement_m < curve[k].displacement_m + window_m) ++j;
    if (j < curve.size()) {
      ss += std::pow(curve[j].smoothed_shear_stress_pa - curve[k].smoothed_shear_stress_pa, 2);
      ++nd;
    }
    if (curve[k].displacement_m >= end - window_m) {
      tail += curve[k].smoothed_shear_stress_pa;
      ++nt;
    }
  }
  const double noise = nd > 1 ? std::sqrt(ss / static_cast<double>(nd) / 2.0) : 0.0;
  return tail / static_cast<double>(nt) < curve[imax].smoothed_shear_stress_pa - 2.0 * noise ? "peak"
                                                                                               : "plateau";
}

ShearFailure read_failure(const std::vector<ShearSample>& curve, double failure_displacement_m) {
  ShearFailure f;
  for (const ShearSample& s : curve)
    if (s.displacement_m <= failure_displacement_m && s.smoothed_shear_stress_pa > f.shear_strength_pa) {
      f.shear_strength_pa = s.smoothed_shear_stress_pa;
      f.displacement_m = s.displacement_m;
    }
  return f;
}

}  // namespace seedcal
