#pragma once
// The report of a `seedcal study` directory: every KIND.json found there (multicontact, stiffness,
// tradeoff, moisture) as tables with the paper's numbers beside seedcal's and gnuplot plots:
//   multicontact: rebound height of every drop under HM and HMNR (the same seeds), the paper's means;
//   stiffness:    contact points and rebound height against Young's modulus;
//   tradeoff:     change of the index against the speed-up, per sweep, with the tolerance band;
//   moisture:     the modulus fit and the soaking table.
// Written by `seedcal study` after its JSON, and by `seedcal report DIR` for such a directory.
#include <string>
#include <vector>

#include "reports/document.hpp"

namespace seedcal::reports {

// The study kinds whose KIND.json is in DIR, in report order.
std::vector<std::string> study_outputs(const std::string& dir);

// The report of those files; throws InputError when there are none.
Document build_studies_report(const std::string& dir);

// build_studies_report + write_report (report.html, report.md, report/*); returns the paths.
std::vector<std::string> render_studies_report(const std::string& dir);

}  // namespace seedcal::reports
