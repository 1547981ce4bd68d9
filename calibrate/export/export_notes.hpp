#pragma once
// What every exported file says in its header: where the values come from, and what does not
// carry over exactly to LIGGGHTS-PUBLIC 3.x (docs/export.md lists every case).
#include <string>
#include <vector>

#include "calibrate/export/exported_model.hpp"

namespace seedcal {

// "study \"jinong1-quick\" (out/jinong1-quick), model \"manual-9\": ...", one line each, no comment
// marker.
std::vector<std::string> provenance_lines(const ExportedModel& m);

// One sentence per difference between seedcal's contact model for `m` and the closest LIGGGHTS
// one; never empty (the tangential cap always differs in detail).
std::vector<std::string> carry_over_notes(const ExportedModel& m);

// Shortest text that reads back to the same double ("%.17g" at most).
std::string exact_number_text(double v);

// `lines` as comment lines: each prefixed with `marker` (e.g. "# "), long ones wrapped at `width`.
std::string comment_block(const std::vector<std::string>& lines, const std::string& marker, std::size_t width = 100);

}  // namespace seedcal
