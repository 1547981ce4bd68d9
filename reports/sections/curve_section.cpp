// The point on the solution curve (calibrate/pipeline/curve_stage.cpp): the verification test's
// runs along the target's curve of solutions (or at the box's corners), the line (or plane) fitted
// to them and the point where it meets the experiment, or why the stage did not run.
#include "reports/sections/common.hpp"
#include "reports/sections/sections.hpp"

namespace seedcal::reports {

void add_curve_section(const StudyData& d, Document& doc) {
  if (!d.summary || !d.summary->curve.is_object() || d.summary->curve.empty()) return;
  const nlohmann::json& c = d.summary->curve;
  Section s{"curve", "The point on the solution curve", {}};
  if (c.contains("skipped")) {
    s.paragraph("Not run: " + format_value(c["skipped"]) + ".");
    doc.sections.push_back(std::move(s));
    return;
  }
  const bool on_curve = c.value("mode", std::string("curve")) == "curve";
  s.paragraph(std::string(on_curve ? "The target leaves a curve of solutions in two parameters. "
                                   : "The target's response is flat within its scatter over the box: every point of it is as good a solution. ") +
              "\"" + format_value(c.value("test", nlohmann::json())) + "\" (" + format_value(c.value("choice_rule", nlohmann::json())) +
              ") ran once at each of " + std::to_string(c.value("points", nlohmann::json::array()).size()) +
              (on_curve ? " points along the curve" : " corners (and the centre) of the box") + " under model " +
              format_value(c.value("model", nlohmann::json())) + "; " +
              (on_curve ? "a straight line in the normalised arc length s" : "a plane in the two parameters") +
              " picks the point where it meets the experiment (" + format_value(c.value("experimental_mean", nlohmann::json())) +
              (c.value("experimental_sd", nlohmann::json()).is_null() ? "" : ", sd " + format_value(c["experimental_sd"])) + ").");
  Table t{"curve_points", on_curve ? "Runs along the solution curve" : "Runs at the box's corners", {}, {}, {}};
  if (on_curve) t.columns.push_back("s");
  const auto& pts = c.value("points", nlohmann::json::array());
  std::vector<std::string> names;
  if (!pts.empty())
    for (const auto& [name, v] : member(pts[0], "at").items()) names.push_back(name);
  for (const auto& n : names) t.columns.push_back(n);
  t.columns.insert(t.columns.end(), {format_value(c.value("metric", nlohmann::json())), "seed", "status"});
  for (const auto& p : pts) {
    std::vector<std::string> row;
    if (on_curve) row.push_back(format_value(p.value("s", nlohmann::json())));
    for (const auto& n : names) row.push_back(format_value(member(p, "at").value(n, nlohmann::json())));
    row.push_back(format_value(p.value("value", nlohmann::json())));
    row.push_back(format_value(p.value("seed", nlohmann::json())));
    row.push_back(format_value(p.value("status", nlohmann::json())));
    t.add_row(row);
  }
  const auto& model = member(c, "response_model");
  std::string terms;
  for (const auto& [name, v] : member(model, "coefficients").items())
    terms += (terms.empty() ? "" : ", ") + name + " " + format_value(v) + " (se " + format_value(member(model, "standard_errors").value(name, nlohmann::json())) + ")";
  t.notes.push_back("Fit: " + format_value(model.value("terms", nlohmann::json())) + "; " + terms + "; residual sd " +
                    format_value(model.value("residual_sd", nlohmann::json())) + " on " + format_value(model.value("df", nlohmann::json())) +
                    " df, r2 " + format_value(model.value("r2", nlohmann::json())) + ", p of the slope " +
                    format_value(model.value("p_slope", nlohmann::json())) + ".");
  s.table(std::move(t));
  std::string picked;
  for (const auto& [name, v] : member(c, "picked").items()) picked += (picked.empty() ? "" : ", ") + name + " = " + format_value(v);
  if (c.contains("moved_into_posterior_region")) {
    std::string by;
    for (const char* key : {"picked_by_line", "picked_by_plane"})
      for (const auto& [name, v] : member(c, key).items()) by += (by.empty() ? "" : ", ") + name + " = " + format_value(v);
    s.paragraph(std::string(c.contains("s_picked") ? "The line picked s = " + format_value(c["s_picked"]) : std::string("The plane picked")) +
                ": " + by + "." + (c.contains("at_end") ? " " + format_value(c["at_end"]) + "." : "") +
                (c.contains("note") ? " " + format_value(c["note"]) + "." : "") + " But " +
                format_value(c["moved_into_posterior_region"]) + ": " + picked + ".");
  } else if (c.contains("note")) {
    s.paragraph(format_value(c["note"]) + ": " + picked + ".");
  } else {
    s.paragraph(std::string(c.contains("s_picked") ? "Picked at s = " + format_value(c["s_picked"]) : std::string("Picked")) + ": " + picked + "." +
                (c.contains("at_end") ? " " + format_value(c["at_end"]) + "." : ""));
  }
  doc.sections.push_back(std::move(s));
}

}  // namespace seedcal::reports
