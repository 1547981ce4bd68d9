#include "solver/sim/time_step.hpp"

#include <cmath>
#include <numbers>

namespace seedcal {

double rayleigh_time_step_s(double radius_m, double density_kg_m3, double shear_modulus_pa,
                            double poisson_ratio) {
  return std::numbers::pi * radius_m * std::sqrt(density_kg_m3 / shear_modulus_pa) /
         (0.1631 * poisson_ratio + 0.8766);
}

HertzImpact hertz_impact(double m_star_kg, double r_star_m, double e_star_pa, double speed_m_s) {
  // 2 * int_0^1 (1 - x^{5/2})^{-1/2} dx = 2 * 1.4716...; the integral is sqrt(pi) Gamma(7/5) /
  // Gamma(9/10) = 1.47164.
  constexpr double kContactTimeFactor = 2.94328;
  const double dmax = std::pow(15.0 * m_star_kg * speed_m_s * speed_m_s /
                                   (16.0 * e_star_pa * std::sqrt(r_star_m)), 0.4);
  return {dmax, 4.0 / 3.0 * e_star_pa * std::sqrt(r_star_m) * std::pow(dmax, 1.5),
          kContactTimeFactor * dmax / speed_m_s};
}

}  // namespace seedcal
