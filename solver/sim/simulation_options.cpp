#include "solver/sim/simulation_options.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace seedcal {

namespace {

[[noreturn]] void refuse(const char* key, double value, const char* range) {
  std::ostringstream m;
  m.precision(17);
  m << "Simulation: " << key << " = " << value << " is out of range (allowed: " << range << ")";
  throw std::invalid_argument(m.str());
}

}  // namespace

void require_time_step(double dt_s, const char* where) {
  if (!(dt_s > 0.0) || !std::isfinite(dt_s)) {
    std::ostringstream m;
    m.precision(17);
    m << where << ": dt_s = " << dt_s << " must be > 0 and finite";
    throw std::invalid_argument(m.str());
  }
}

void validate_options(SimulationOptions& o) {
  require_time_step(o.dt_s, "Simulation");
  if (o.threads < 1) o.threads = 1;
  if (!(o.skin_m >= 0.0) || !std::isfinite(o.skin_m)) refuse("skin_m", o.skin_m, "0 (automatic) or > 0 m");
  if (!std::isfinite(o.gravity_m_s2.sum())) refuse("gravity_m_s2", o.gravity_m_s2.norm(), "finite");
  if (o.simd_lanes < 1) refuse("simd_lanes", o.simd_lanes, "1, 4 or 8 (the widest the CPU runs)");
  // The limits of the overlap guard (guards.hpp): a lone sphere at most its radius, a clump's
  // sphere at most twice its own (where the contact point reaches its centre).
  const GuardOptions& g = o.guards;
  if (!(g.max_overlap_fraction > 0.0 && g.max_overlap_fraction <= 1.0))
    refuse("guards.max_overlap_fraction", g.max_overlap_fraction, "(0, 1]");
  if (!(g.max_clump_sphere_overlap_fraction > 0.0 && g.max_clump_sphere_overlap_fraction <= 2.0))
    refuse("guards.max_clump_sphere_overlap_fraction", g.max_clump_sphere_overlap_fraction, "(0, 2]");
  if (!(g.max_energy_factor > 0.0)) refuse("guards.max_energy_factor", g.max_energy_factor, "> 0");
  if (g.check_interval < 1) refuse("guards.check_interval", g.check_interval, ">= 1 step");
  if (!(o.contact.epsd_damping_ratio >= 0.0) || !std::isfinite(o.contact.epsd_damping_ratio))
    refuse("contact.epsd_damping_ratio", o.contact.epsd_damping_ratio, ">= 0");
  const FrameObserver& f = o.observer;
  if (f.on_frame && !(f.interval_s > 0.0))
    throw std::invalid_argument("Simulation: a frame observer needs interval_s > 0");
  if (f.on_progress && !(f.progress_interval_s > 0.0))
    throw std::invalid_argument("Simulation: a progress observer needs progress_interval_s > 0");
}

}  // namespace seedcal
