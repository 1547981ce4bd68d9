// Final summary from summary.json: the calibrated values (and those held at nominal), the
// confirmed mean, sd, relative error and interval per target, whether the study converged, and its
// cost: DEM runs against the classical DOE workflow's count, CPU and wall seconds.
#include <cmath>

#include "reports/sections/common.hpp"
#include "reports/sections/sections.hpp"

namespace seedcal::reports {

void add_summary_section(const StudyData& d, Document& doc) {
  const auto& j = d.summary;
  if (j.empty()) return;
  Section s{"summary", "Final summary", {}};
  Table run{"summary", "Study outcome and cost", {"item", "value"}, {}, {}};
  auto row = [&](const std::string& label, const char* key) {
    if (j.contains(key)) run.add_row({label, format_value(j[key])});
  };
  row("stage reached", "stage_reached");
  row("converged", "converged");
  row("confirmation rounds", "confirmation_rounds");
  row("DEM evaluations (calibration)", "evaluations");
  row("DEM evaluations (with verification)", "evaluations_total");
  row("  of which answered from the store", "evaluations_from_store");
  row("classical workflow (PB + path + CCD, 3 replicates, + 3 confirmations; every target's test at each point)", "classical_workflow_evaluations");
  const double used = as_number(j.value("evaluations", nlohmann::json())), classical = as_number(j.value("classical_workflow_evaluations", nlohmann::json()));
  if (std::isfinite(used) && std::isfinite(classical) && classical > 0)
    run.add_row({"evaluations / classical workflow", format_number(used / classical, 3)});
  row("CPU seconds (DEM runs)", "cpu_seconds");
  row("  calibration", "calibration_cpu_seconds");
  row("  verification", "verification_cpu_seconds");
  row("wall seconds (all sessions)", "wall_seconds");
  if (j.contains("tolerance") && j["tolerance"].is_number()) run.add_row({"tolerance", format_number(100.0 * j["tolerance"].get<double>()) + " %"});
  s.table(std::move(run));

  Table cal{"calibrated_values", "Parameter values", {"parameter", "value", "role"}, {}, {}};
  for (const auto& [p, v] : member(j, "calibrated").items()) cal.add_row({p, format_value(v), "calibrated"});
  for (const auto& [p, v] : member(j, "held_at_nominal").items()) cal.add_row({p, format_value(v), "held at nominal"});
  if (!cal.rows.empty()) s.table(std::move(cal));
  else s.note("No calibrated values yet (the study stopped at stage " + j.value("stage_reached", std::string("?")) + ")");

  Table conf{"confirmed", "Confirmation at the calibrated values (last round)",
             {"metric", "target", "n", "mean", "sd", "relative error", "CI low", "CI high", "within tolerance", "resolved",
              "replicates to resolve the tolerance"}, {}, {}};
  for (const auto& [metric, m] : member(j, "confirmed").items()) {
    const auto ci = m.value("rel_error_ci", nlohmann::json::array());
    conf.add_row({metric, format_value(m.value("target", nlohmann::json())), format_value(m.value("n", nlohmann::json())),
                  format_value(m.value("mean", nlohmann::json())), format_value(m.value("sd", nlohmann::json())),
                  format_percent(m.value("rel_error", nlohmann::json())), format_percent(ci.size() > 0 ? ci[0] : nlohmann::json()),
                  format_percent(ci.size() > 1 ? ci[1] : nlohmann::json()), format_value(m.value("within_tolerance", nlohmann::json())),
                  format_value(m.value("resolved", nlohmann::json())), format_value(m.value("replicates_to_resolve_tolerance", nlohmann::json()))});
  }
  if (!conf.rows.empty()) {
    conf.notes.push_back("Resolved: the whole confidence interval lies within the tolerance; the replicate count is the "
                         "estimate n >= (t sd / (tolerance |target|))^2.");
    s.table(std::move(conf));
  }
  doc.sections.push_back(std::move(s));
}

}  // namespace seedcal::reports
