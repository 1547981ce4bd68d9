// The report's first screen: the answer. The calibrated values with their 95 % credible intervals
// and whether each is identified (with the reason), the confirmation against the target, the
// verification tests against the laboratory, the chosen clump model with the comparison that chose
// it, and what the scenes warned about their rigs. The inputs and the stage-by-stage detail
// follow in the later sections.
#include <cmath>

#include "reports/sections/common.hpp"
#include "reports/sections/sections.hpp"

namespace seedcal::reports {

void add_answer_section(const StudyData& d, Document& doc) {
  if (!d.summary) return;
  const StudySummary& j = *d.summary;
  Section s{"answer", "The answer", {}};
  const auto& interval = j.calibrated_interval;
  const auto& identified = j.identified;
  const auto& posterior = j.posterior;
  Table cal{"answer_parameters", "Calibrated values, their 95 % credible intervals and whether the data identify them",
            {"parameter", "calibrated", "95 % interval", "identified", "why"}, {}, {}};
  for (const auto& [p, v] : j.calibrated) {
    std::string iv = "n/a";
    if (const auto it = interval.find(p); it != interval.end())
      iv = format_value(it->second[0]) + " .. " + format_value(it->second[1]);
    std::string why = member(posterior, "reasons").contains(p) ? format_value(member(posterior, "reasons")[p]) : "";
    if (member(posterior, "at_edge").contains(p)) why += "; the calibrated value lies " + format_value(member(posterior, "at_edge")[p]);
    cal.add_row({p, format_value(v), iv, identified.count(p) ? format_value(identified.at(p)) : "n/a", why});
  }
  if (!cal.rows.empty()) {
    for (const auto& t : member(posterior, "targets"))
      cal.notes.push_back(std::string(t.contains("role") ? "Test " : "Target ") + format_value(t.value("name", nlohmann::json())) + ": " +
                          format_value(t.value("uncertainty", nlohmann::json())) + "; run-to-run sd " +
                          format_value(t.value("run_noise_sd", nlohmann::json())) + " from " +
                          format_value(t.value("run_noise_source", nlohmann::json())) + ".");
    // The point as a whole: inside the joint 95 % highest-density region or not (a point can lie
    // inside every parameter's interval and still off a posterior bent along a curve, or outside a
    // flat parameter's central interval and still where the data favour it most).
    const auto& in_region = member(posterior, "in_hpd95");
    if (in_region.contains("calibrated"))
      cal.notes.push_back(std::string("The calibrated point lies ") + (in_region["calibrated"].get<bool>() ? "inside" : "outside") +
                          " the posterior's joint 95 % highest-density region.");
    s.table(std::move(cal));
    const auto& curve = j.curve;
    if (!curve.empty() && !curve.contains("skipped")) {
      std::string picked;
      for (const auto& [name, v] : member(curve, "picked").items()) picked += (picked.empty() ? "" : ", ") + name + " " + format_value(v);
      s.paragraph("The point on the solution curve was picked by \"" + format_value(curve.value("test", nlohmann::json())) + "\" (" +
                  std::to_string(curve.value("points", nlohmann::json::array()).size()) + " runs along it): " + picked +
                  (curve.contains("note") ? " (" + format_value(curve["note"]) + ")" : "") +
                  "; the intervals above combine the target with that test (section \"The point on the solution curve\").");
    }
  } else {
    s.note("No calibrated values yet (the study stopped at stage " + (j.stage_reached.empty() ? "?" : j.stage_reached) + ").");
  }

  Table lab{"answer_tests", "Against the laboratory", {"test", "role", "simulated mean", "sd", "laboratory", "relative error"}, {}, {}};
  for (const auto& [metric, m] : j.confirmed) {
    const nlohmann::json none;
    lab.add_row({metric, "target (confirmation)", format_value(m.stats ? nlohmann::json(m.stats->mean) : none),
                 format_value(m.stats ? nlohmann::json(m.stats->sd) : none), format_value(m.target),
                 format_percent(m.stats ? nlohmann::json(m.stats->rel_error) : none)});
  }
  for (const auto& t : member(j.verification, "tests")) {
    if (t.value("role", std::string()) == "target") continue;
    std::string lab_value = format_value(t.value("experimental_mean", nlohmann::json()));
    if (!t.value("experimental_sd", nlohmann::json()).is_null()) lab_value += " (sd " + format_value(t["experimental_sd"]) + ")";
    lab.add_row({format_value(t.value("test", nlohmann::json())), "verification", format_value(t.value("mean", nlohmann::json())),
                 format_value(t.value("sd", nlohmann::json())), lab_value, format_percent(t.value("rel_error", nlohmann::json()))});
  }
  if (!lab.rows.empty()) s.table(std::move(lab));

  const auto& sel = j.model_selection;
  if (!sel.empty() && !sel.value("chosen", nlohmann::json()).is_null()) {
    std::string text = "Chosen clump model: " + format_value(sel["chosen"]);
    if (!sel.value("most_accurate", nlohmann::json()).is_null() && sel["most_accurate"] != sel["chosen"])
      text += " (the most accurate is " + format_value(sel["most_accurate"]) + ")";
    text += ". " + format_value(sel.value("comparison", nlohmann::json("")));
    if (sel.contains("tied") && sel["tied"].size() > 1) {
      std::string ties;
      for (const auto& m : sel["tied"]) ties += (ties.empty() ? "" : ", ") + format_value(m);
      text += ". Tied within the scatter: " + ties;
    }
    s.paragraph(text + ".");
  }
  // The rigs' warnings (a box a few seeds across, say): every number above was measured on them.
  if (!j.warnings.empty()) {
    s.paragraph("The scenes warned about their rigs before the first run; every result above was measured on "
                "these rigs:");
    for (const std::string& w : j.warnings) s.note(w);
  }
  doc.sections.push_back(std::move(s));
}

}  // namespace seedcal::reports
