// Final summary from summary.json: the calibrated values (and those held at nominal), the
// confirmed mean, sd, relative error and interval per target, whether the study converged, and its
// cost: DEM runs against the classical DOE workflow's count, CPU and wall seconds.
#include <cmath>

#include "reports/sections/common.hpp"
#include "reports/sections/sections.hpp"

namespace seedcal::reports {

void add_summary_section(const StudyData& d, Document& doc) {
  if (!d.summary) return;
  const StudySummary& j = *d.summary;
  Section s{"summary", "Final summary", {}};
  Table run{"summary", "Study outcome and cost", {"item", "value"}, {}, {}};
  auto row = [&](const std::string& label, const nlohmann::json& value) { run.add_row({label, format_value(value)}); };
  row("stage reached", j.stage_reached);
  row("converged", j.converged);
  row("confirmation rounds", j.confirmation_rounds);
  row("DEM evaluations (calibration)", j.evaluations);
  row("DEM evaluations (with verification)", j.evaluations_total);
  row("  of which answered from the store", j.evaluations_from_store);
  row("classical workflow (PB + path + CCD, 3 replicates, + 3 confirmations; every target's test at each point)",
      j.classical_workflow_evaluations);
  if (j.classical_workflow_evaluations > 0)
    run.add_row({"evaluations / classical workflow",
                 format_number(static_cast<double>(j.evaluations) / j.classical_workflow_evaluations, 3)});
  row("CPU seconds (DEM runs)", j.cpu_seconds);
  row("  calibration", j.calibration_cpu_seconds);
  row("  verification", j.verification_cpu_seconds);
  row("wall seconds (all sessions)", j.wall_seconds);
  if (std::isfinite(j.tolerance)) run.add_row({"tolerance", format_number(100.0 * j.tolerance) + " %"});
  s.table(std::move(run));

  Table cal{"calibrated_values", "Parameter values", {"parameter", "value", "role"}, {}, {}};
  for (const auto& [p, v] : j.calibrated) cal.add_row({p, format_value(v), "calibrated"});
  for (const auto& [p, v] : j.held_at_nominal) cal.add_row({p, format_value(v), "held at nominal"});
  if (!cal.rows.empty()) s.table(std::move(cal));
  else s.note("No calibrated values yet (the study stopped at stage " + (j.stage_reached.empty() ? "?" : j.stage_reached) + ")");

  Table conf{"confirmed", "Confirmation at the calibrated values (last round)",
             {"metric", "target", "n", "mean", "sd", "relative error", "CI low", "CI high", "within tolerance", "resolved",
              "replicates to resolve the tolerance"}, {}, {}};
  const nlohmann::json none;
  for (const auto& [metric, m] : j.confirmed) {
    const ConfirmedStats* x = m.stats ? &*m.stats : nullptr;
    conf.add_row({metric, format_value(m.target), format_value(m.samples.size()), format_value(x ? nlohmann::json(x->mean) : none),
                  format_value(x ? nlohmann::json(x->sd) : none), format_percent(x ? nlohmann::json(x->rel_error) : none),
                  format_percent(x ? nlohmann::json(x->rel_error_ci[0]) : none), format_percent(x ? nlohmann::json(x->rel_error_ci[1]) : none),
                  format_value(x ? nlohmann::json(x->within_tolerance) : none), format_value(x ? nlohmann::json(x->resolved) : none),
                  format_value(x ? nlohmann::json(x->replicates_to_resolve_tolerance) : none)});
  }
  if (!conf.rows.empty()) {
    conf.notes.push_back("Resolved: the whole confidence interval lies within the tolerance; the replicate count is the "
                         "estimate n >= (t sd / (tolerance |target|))^2.");
    s.table(std::move(conf));
  }
  doc.sections.push_back(std::move(s));
}

}  // namespace seedcal::reports
