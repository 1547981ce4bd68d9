#pragma once
// Helpers the section builders share.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "reports/document.hpp"
#include "reports/gnuplot_svg.hpp"
#include "reports/study_data.hpp"

namespace seedcal::reports {

// Draws the plot into report/<id>.svg (by reference from the Document), or, when gnuplot fails,
// adds a note saying why the plot is missing.
void add_plot(Section& section, const std::string& id, const std::string& caption, const GnuplotPlot& plot);

// The note for data an older study store does not have.
std::string needs_newer_store(const std::string& what);

// Strings of a JSON array (non-strings left out); empty when not an array.
std::vector<std::string> strings_of(const nlohmann::json& array);

// The member `key` of an object by reference, or a null value when absent or not an object (a
// null iterates as empty). Unlike json::value(key, default), it makes no copy, so
// `for (... : member(j, "k").items())` never iterates a destroyed temporary.
const nlohmann::json& member(const nlohmann::json& object, const std::string& key);

// A JSON number or NaN (null, absent, not a number).
double as_number(const nlohmann::json& v);

// The factors the surrogate stages vary: the surrogate design's "factors", else the solve stage's,
// else the screening stage's "kept".
std::vector<std::string> kept_factors(const StudyData& d);

// Target names in study order: from the last solve round, else the screening stage.
std::vector<std::string> target_names(const StudyData& d);

// An id suffix for the t-th of n targets: "" when there is one, "_<name>" otherwise.
std::string target_suffix(const std::vector<std::string>& names, std::size_t t);

// gnuplot's left margin (characters) wide enough for the longest label.
int label_margin(const std::vector<std::string>& labels);

}  // namespace seedcal::reports
