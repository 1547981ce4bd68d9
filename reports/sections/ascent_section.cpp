// Steepest ascent: the path from the screening centre along the first-order model of the primary
// target (coded and natural settings, DEM response per step), why it stopped, and the box the
// response-surface design is placed in.
#include "reports/sections/common.hpp"
#include "reports/sections/sections.hpp"

namespace seedcal::reports {

void add_ascent_section(const StudyData& d, Document& doc) {
  const auto* a = d.stage("ascent");
  if (!a) return;
  Section s{"ascent", "Steepest ascent", {}};
  const auto factors = strings_of(d.stage("screen") ? (*d.stage("screen"))["kept"] : nlohmann::json::array());
  s.paragraph("Primary target " + a->value("target", std::string("?")) + " = " + format_value(a->value("target_value", nlohmann::json())) +
              "; response at the screening centre (first-order model) " + format_value(a->value("centre_response", nlohmann::json())) + ".");
  if (a->contains("skipped")) s.paragraph("No path was run: " + (*a)["skipped"].get<std::string>() + ".");
  if (a->contains("direction"))
    s.paragraph("Path of steepest " + (*a)["direction"].get<std::string>() + ", step (coded) " + format_value((*a)["step_coded"]) +
                "; stopped: " + a->value("stop_reason", std::string("n/a")) + ".");
  const auto& points = a->value("points", nlohmann::json::array());
  if (!points.empty()) {
    Table t{"ascent_path", "Path of steepest ascent/descent (coded units of the screening range, then natural)", {"step"}, {}, {}};
    for (const auto& f : factors) t.columns.push_back(f + " (coded)");
    for (const auto& f : factors) t.columns.push_back(f);
    t.columns.push_back("response");
    int step = 0;
    for (const auto& p : points) {
      std::vector<std::string> row{std::to_string(++step)};
      const auto& c = p.value("coded", nlohmann::json::array());
      const auto& n = p.value("natural", nlohmann::json::array());
      for (std::size_t j = 0; j < factors.size(); ++j) row.push_back(j < c.size() ? format_value(c[j]) : "n/a");
      for (std::size_t j = 0; j < factors.size(); ++j) row.push_back(j < n.size() ? format_value(n[j]) : "n/a");
      row.push_back(format_value(p.value("response", nlohmann::json())));
      t.add_row(std::move(row));
    }
    s.table(std::move(t));
  }
  if (a->contains("surrogate_box") && (*a)["surrogate_box"].is_object()) {
    Table t{"surrogate_box", "Surrogate box (where the response-surface design is placed)", {"factor", "low", "high"}, {}, {}};
    for (const auto& [f, range] : (*a)["surrogate_box"].items())
      t.add_row({f, range.size() > 0 ? format_value(range[0]) : "n/a", range.size() > 1 ? format_value(range[1]) : "n/a"});
    s.table(std::move(t));
  }
  doc.sections.push_back(std::move(s));
}

}  // namespace seedcal::reports
