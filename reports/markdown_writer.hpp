#pragma once
// report.md: the Markdown twin of report.html (CommonMark with GitHub tables); plots are linked
// as files (report/<id>.svg, scenes/<name>/<picture>.svg), each table links its CSV.
#include <string>
#include <string_view>

#include "reports/document.hpp"

namespace seedcal::reports {

// Backslash-escapes the characters Markdown would read as markup (\ ` * _ [ ] < > | #) and turns
// line breaks into spaces, so any text fits on one line and in a table cell.
std::string escape_markdown(std::string_view text);

std::string render_markdown(const Document& doc);

}  // namespace seedcal::reports
