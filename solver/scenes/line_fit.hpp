#pragma once
// Least-squares line fits for the angle indices (heap side, drum free surface).
#include <vector>

namespace seedcal {

struct LineFit {
  double intercept = 0.0, slope = 0.0, r2 = 0.0;
  std::size_t points = 0;
  bool ok = false;
};

// Ordinary least squares z = a + b x (Eigen QR; needs at least 3 points with distinct x).
LineFit fit_line(const std::vector<double>& x, const std::vector<double>& z);

// Upper envelope of a cloud of circles (x, z_top) in columns of width `bin`: per column the highest
// top, returned as (column centre, height) pairs for columns that hold any circle.
std::vector<std::pair<double, double>> upper_profile(const std::vector<std::pair<double, double>>& x_top,
                                                     double bin);

}  // namespace seedcal
