#include "calibrate/scenes/scene_schema.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

namespace seedcal {

std::string schema_number_text(double v) {
  // The fewest digits that read back as v: plain decimals between 1e-4 and 1e6 (0.0618, 0.0002,
  // 10, 200000), else the exponent form (1e-05, 1e+08).
  char buf[48];
  const bool plain = v == 0.0 || (std::fabs(v) >= 1e-4 && std::fabs(v) < 1e6);
  for (int digits = plain ? 0 : 1; digits <= 17; ++digits) {
    std::snprintf(buf, sizeof buf, plain ? "%.*f" : "%.*g", digits, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
}

std::string schema_range_text(const Range& r) {
  if (r.hi >= 1e307) return (r.lo_open ? "> " : ">= ") + schema_number_text(r.lo);
  if (r.lo <= -1e307) return (r.hi_open ? "< " : "<= ") + schema_number_text(r.hi);
  return (r.lo_open ? "(" : "[") + schema_number_text(r.lo) + ", " + schema_number_text(r.hi) + (r.hi_open ? ")" : "]");
}

const std::vector<SchemaMetric>& run_report_metrics() {
  // add_run_report (scene_registry.cpp) and add_seed_scene_keys (seed_scene_common.hpp).
  static const std::vector<SchemaMetric> kMetrics = {
      {"cpu_seconds", "s", "CPU time of the run (every thread)"},
      {"wall_seconds", "s", "elapsed time of the run"},
      {"steps", "", "time steps taken"},
      {"bodies", "", "bodies (seeds) in the scene at the end"},
      {"spheres", "", "spheres of those bodies"},
      {"dt_s", "s", "time step"},
      {"stop_reason", "", "why the run ended"},
      {"status", "", "`ok`, or the guard that stopped the run"},
      {"deepest_overlap_fraction", "",
       "deepest overlap over the smaller sphere's radius where it passed half of it (beyond Hertz "
       "theory's small-overlap range; only a clump's spheres go on past it), 0 when none did"},
      {"failure", "", "where and why a stopped run failed: step, time_s, body, message"},
      {"phases", "", "each phase of the protocol as it ran, named as in `plan`: name, simulated_s, steps, cpu_seconds"},
      {"fidelity", "", "the rig the run used (`paper` or `quick`)"},
      {"particle", "", "the seed model: clump file or inline spheres, size distribution"},
  };
  return kMetrics;
}

std::string keys_markdown(const SchemaTable& t) {
  std::ostringstream s;
  s << "Keys of " << t.table << " (`seedcal keys " << t.kind << "`):\n\n"
    << "| key | unit | meaning | range | default |\n|---|---|---|---|---|\n";
  for (const SchemaKey& k : t.keys)
    s << "| `" << k.key << "` | " << k.unit << " | " << k.meaning << " | " << k.range << " | " << k.default_text
      << " |\n";
  return s.str();
}

std::string metrics_markdown(const SchemaTable& t) {
  std::ostringstream s;
  s << "Metrics (`metrics.json`) besides the run report's:\n\n| key | unit | meaning |\n|---|---|---|\n";
  for (const SchemaMetric& m : t.metrics) s << "| `" << m.key << "` | " << m.unit << " | " << m.meaning << " |\n";
  return s.str();
}

std::string run_report_markdown() {
  std::ostringstream s;
  s << "| key | unit | meaning |\n|---|---|---|\n";
  for (const SchemaMetric& m : run_report_metrics()) s << "| `" << m.key << "` | " << m.unit << " | " << m.meaning << " |\n";
  return s.str();
}

std::vector<SchemaTable> scene_schema_tables() {
  return {free_drop_schema_table(), bulk_density_schema_table(), direct_shear_schema_table(),
          piling_schema_table(), drum_schema_table()};
}

}  // namespace seedcal
