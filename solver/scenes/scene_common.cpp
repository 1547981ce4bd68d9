#include "solver/scenes/scene_common.hpp"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <limits>
#include <numbers>
#include <sstream>

#include "solver/core/errors.hpp"
#include "solver/sim/time_step.hpp"

namespace seedcal {

double TimeStepLimits::stable_limit_s() const {
  return contact_time_s > 0.0 ? std::min(rayleigh_s, 0.1 * contact_time_s) : rayleigh_s;
}

TimeStepLimits time_step_limits(const Simulation& sim, double expected_impact_speed_m_s) {
  TimeStepLimits lim;
  lim.rayleigh_s = sim.rayleigh_time_step_s();
  lim.impact_speed_m_s = expected_impact_speed_m_s;
  const auto& S = sim.spheres();
  const auto& table = sim.table();
  // The sphere with the smallest Rayleigh step, named for the message.
  for (std::size_t i = 0; i < S.size(); ++i) {
    const Material& m = table.materials()[S.material[i]];
    if (rayleigh_time_step_s(S.radius_m[i], m.density_kg_m3, m.shear_modulus_pa(), m.poisson_ratio) >
        lim.rayleigh_s)
      continue;
    std::ostringstream w;
    w << "'" << m.name << "' sphere r = " << S.radius_m[i] << " m, E = " << m.youngs_modulus_pa
      << " Pa, nu = " << m.poisson_ratio << ", density " << m.density_kg_m3 << " kg/m3";
    lim.rayleigh_from = w.str();
    break;
  }
  if (expected_impact_speed_m_s <= 0.0) return lim;
  // Shortest contact: the smallest sphere of each material (as a lone sphere: the smallest mass)
  // against every material it can touch, walls included.
  const std::size_t nm = table.material_count();
  std::vector<double> r_min(nm, std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < S.size(); ++i)
    r_min[S.material[i]] = std::min(r_min[S.material[i]], S.radius_m[i]);
  double tc = std::numeric_limits<double>::infinity();
  for (std::size_t a = 0; a < nm; ++a) {
    if (!std::isfinite(r_min[a])) continue;
    const double ra = r_min[a];
    const double ma = table.materials()[a].density_kg_m3 * 4.0 / 3.0 * std::numbers::pi * ra * ra * ra;
    for (std::size_t b = 0; b < nm; ++b) {
      const PairConstants& pc = table.pair(static_cast<std::uint16_t>(a), static_cast<std::uint16_t>(b));
      if (!pc.defined) continue;
      // Against a sphere of its own size (if b has spheres) or a wall (infinite radius and mass).
      const bool b_has_spheres = std::isfinite(r_min[b]);
      const double rstar = b_has_spheres ? ra * r_min[b] / (ra + r_min[b]) : ra;
      const double mb = b_has_spheres ? table.materials()[b].density_kg_m3 * 4.0 / 3.0 *
                                            std::numbers::pi * std::pow(r_min[b], 3)
                                      : std::numeric_limits<double>::infinity();
      const double mstar = std::isfinite(mb) ? ma * mb / (ma + mb) : ma;
      const double t = hertz_impact(mstar, rstar, pc.e_star_pa, expected_impact_speed_m_s).contact_time_s;
      if (t < tc) {
        tc = t;
        std::ostringstream w;
        w << "'" << table.materials()[a].name << "' (r = " << ra << " m) on '"
          << table.materials()[b].name << "'";
        lim.contact_from = w.str();
      }
    }
  }
  lim.contact_time_s = std::isfinite(tc) ? tc : 0.0;
  return lim;
}

double choose_time_step(const TimeStepSpec& spec, const TimeStepLimits& limits) {
  const double limit = limits.stable_limit_s();
  std::ostringstream why;
  why << "the stable limit is " << limit << " s (Rayleigh step " << limits.rayleigh_s << " s";
  if (!limits.rayleigh_from.empty()) why << " of the " << limits.rayleigh_from;
  if (limits.contact_time_s > 0.0) {
    why << "; a tenth of the Hertz contact time";
    if (!limits.contact_from.empty()) why << " of " << limits.contact_from;
    why << " at " << limits.impact_speed_m_s << " m/s is " << 0.1 * limits.contact_time_s << " s";
  }
  why << ")";
  if (spec.dt_s > 0.0) {
    if (spec.dt_s > limit && !spec.force_dt) {
      std::ostringstream m;
      m << "= " << spec.dt_s << " s is above the stable limit: " << why.str()
        << "; use at most " << limit << " s, or set force_dt = true to run anyway";
      throw SettingError("dt_s", m.str());
    }
    return spec.dt_s;
  }
  if (!(spec.rayleigh_fraction > 0.0)) {
    throw SettingError("rayleigh_fraction", "= " + std::to_string(spec.rayleigh_fraction) +
                                                ": must be in (0, 1]");
  }
  const double dt = spec.rayleigh_fraction * limits.rayleigh_s;
  if (dt > limit && !spec.rayleigh_fraction_set && !spec.force_dt) return limit;
  if (dt > limit && !spec.force_dt) {
    std::ostringstream m;
    m << "= " << spec.rayleigh_fraction << " gives dt_s = " << dt << " s, above the stable limit: "
      << why.str() << "; use rayleigh_fraction <= " << limit / limits.rayleigh_s
      << " or set force_dt = true";
    throw SettingError("rayleigh_fraction", m.str());
  }
  return dt;
}

double run_cpu_seconds(int threads) {
  timespec ts{};
  clock_gettime(threads > 1 ? CLOCK_PROCESS_CPUTIME_ID : CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

}  // namespace seedcal
