#include "reports/sections/common.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace seedcal::reports {

void add_plot(Section& section, const std::string& id, const std::string& caption, const GnuplotPlot& plot) {
  try {
    section.plot(Plot{id, caption, render_gnuplot_svg(plot), "report/" + id + ".svg", true});
  } catch (const std::exception& e) {
    section.note("The plot \"" + caption + "\" could not be drawn: " + e.what());
  }
}

std::string needs_newer_store(const std::string& what) {
  return "Needs a newer study store: " + what +
         " (this store was written by a seedcal that did not record it; resume the study with --resume, or run it again, "
         "to add it)";
}

std::vector<std::string> strings_of(const nlohmann::json& array) {
  std::vector<std::string> out;
  if (!array.is_array()) return out;
  for (const auto& v : array)
    if (v.is_string()) out.push_back(v.get<std::string>());
  return out;
}

const nlohmann::json& member(const nlohmann::json& object, const std::string& key) {
  static const nlohmann::json null_value;
  if (!object.is_object()) return null_value;
  const auto it = object.find(key);
  return it == object.end() ? null_value : *it;
}

double as_number(const nlohmann::json& v) {
  return v.is_number() ? v.get<double>() : std::numeric_limits<double>::quiet_NaN();
}

std::vector<std::string> kept_factors(const StudyData& d) {
  if (const auto* s = d.stage("surrogate_design"); s && s->contains("factors")) return strings_of((*s)["factors"]);
  if (const int r = d.last_solve_round(); r > 0) {
    const auto* s = d.stage(std::string("solve_round_") + std::to_string(r));
    if (s && s->contains("factors")) return strings_of((*s)["factors"]);
  }
  if (const auto* s = d.stage("screen"); s && s->contains("kept")) return strings_of((*s)["kept"]);
  return {};
}

std::vector<std::string> target_names(const StudyData& d) {
  std::vector<std::string> out;
  const nlohmann::json* source = nullptr;
  if (const int r = d.last_solve_round(); r > 0) source = d.stage(std::string("solve_round_") + std::to_string(r));
  if (!source) source = d.stage("screen");
  if (source && source->contains("targets") && (*source)["targets"].is_array())
    for (const auto& t : (*source)["targets"]) out.push_back(t.value("name", std::string("target")));
  return out;
}

std::string target_suffix(const std::vector<std::string>& names, std::size_t t) {
  if (names.size() <= 1 || t >= names.size()) return "";
  std::string suffix = "_";
  return suffix += file_stem(names[t]);
}

int label_margin(const std::vector<std::string>& labels) {
  std::size_t longest = 4;
  for (const auto& l : labels) longest = std::max(longest, l.size());
  return static_cast<int>(std::min<std::size_t>(longest, 48)) + 2;
}

}  // namespace seedcal::reports
