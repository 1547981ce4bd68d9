#include "calibrate/clumps/moisture.hpp"

#include <cmath>

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_fit.h>
#include <gsl/gsl_statistics_double.h>

#include "store/errors.hpp"

namespace seedcal {
namespace {

LineFit line_fit(const std::vector<double>& x, const std::vector<double>& y, std::string model) {
  LineFit f;
  f.model = std::move(model);
  f.n = static_cast<int>(x.size());
  gsl_fit_linear(x.data(), 1, y.data(), 1, x.size(), &f.c0, &f.c1, &f.cov00, &f.cov01, &f.cov11,
                 &f.sumsq);
  const double var_y = gsl_stats_variance(y.data(), 1, y.size());
  const double tss = var_y * static_cast<double>(y.size() - 1);
  f.r2 = tss > 0 ? 1.0 - f.sumsq / tss : 1.0;
  // gsl_fit_linear's covariance uses s^2 = sumsq / (n - 2), so sqrt(cov11) is the slope's SE.
  f.se_c1 = std::sqrt(f.cov11);
  f.t_c1 = f.se_c1 > 0 ? f.c1 / f.se_c1 : 0.0;
  f.p_c1 = f.se_c1 > 0 ? 2.0 * gsl_cdf_tdist_Q(std::abs(f.t_c1), f.n - 2.0) : 0.0;
  return f;
}

}  // namespace

double ModulusFit::youngs_modulus_pa(double w) const {
  return std::exp(log_linear.c0 + log_linear.c1 * w);
}

ModulusFit fit_modulus(const Variety& v) {
  if (v.mc_moisture_fraction.size() < 3)
    throw InputError(v.file + ": moisture_modulus: a fit with statistics needs at least 3 points");
  ModulusFit m;
  m.linear = line_fit(v.mc_moisture_fraction, v.mc_youngs_modulus_pa, "E = c0 + c1 w");
  std::vector<double> ln_e;
  for (double e : v.mc_youngs_modulus_pa) ln_e.push_back(std::log(e));
  m.log_linear = line_fit(v.mc_moisture_fraction, ln_e, "ln E = c0 + c1 w");
  m.flag = v.mc_flag;
  return m;
}

Vec3 soaking_growth(const Variety& v, double hours) {
  if (v.soak_hours.empty() || hours <= 0.0) return Vec3::Ones();
  auto ratio = [&](std::size_t i) { return Vec3(v.soak_after_m[i].cwiseQuotient(v.soak_before_m[i])); };
  double t0 = 0.0;
  Vec3 g0 = Vec3::Ones();
  for (std::size_t i = 0; i < v.soak_hours.size(); ++i) {
    const Vec3 g1 = ratio(i);
    if (hours <= v.soak_hours[i]) {
      const double f = (hours - t0) / (v.soak_hours[i] - t0);
      return g0 + f * (g1 - g0);
    }
    t0 = v.soak_hours[i];
    g0 = g1;
  }
  return g0;
}

}  // namespace seedcal
