#pragma once
// Moisture relations of a variety: Young's modulus against moisture content (Table 3) fitted by
// least squares with its statistics, and the tri-axial growth of a seed with soaking (Table 2), so
// a clump and a material can be made for a given moisture or soaking time.
#include <string>

#include "calibrate/clumps/variety.hpp"

namespace seedcal {

// y = c0 + c1 x by gsl_fit_linear, with its statistics.
struct LineFit {
  std::string model;       // "E = c0 + c1 w" or "ln E = c0 + c1 w"
  int n = 0;
  double c0 = 0, c1 = 0, cov00 = 0, cov01 = 0, cov11 = 0;
  double sumsq = 0;        // residual sum of squares (in the fitted y)
  double r2 = 0;           // coefficient of determination (in the fitted y)
  double se_c1 = 0;        // standard error of the slope
  double t_c1 = 0, p_c1 = 0;  // t statistic and two-sided p-value of the slope (n - 2 dof)
};

struct ModulusFit {
  LineFit linear;      // E in Pa against moisture fraction
  LineFit log_linear;  // ln(E / Pa) against moisture fraction: the modulus falls exponentially
  std::string flag;    // the data file's note on questionable values (all values are fitted)
  // E at a moisture fraction from the log-linear fit (positive everywhere), Pa.
  double youngs_modulus_pa(double moisture_fraction) const;
};

// Throws InputError when the variety has fewer than 3 moisture-modulus points.
ModulusFit fit_modulus(const Variety& v);

// Mean growth ratio after/before soaking per axis (L, W, T) at `hours`: the Table 2 ratios
// interpolated linearly in time from 1 at 0 h, held at the last row's beyond it.
Vec3 soaking_growth(const Variety& v, double hours);

}  // namespace seedcal
