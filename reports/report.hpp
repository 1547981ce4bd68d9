#pragma once
// `seedcal report DIR` and the end of `seedcal calibrate`: a study directory rendered as
//   DIR/report.html   self-contained (inline CSS and SVG plots, no scripts)
//   DIR/report.md     the same content in Markdown, plots linked as files
//   DIR/report/       every table as <id>.csv and every plot as <id>.svg
// Every file is written atomically (temporary file + rename); files a previous rendering left in
// DIR/report/ that this one does not write are removed. See docs/reports.md.
#include <string>
#include <vector>

#include "reports/document.hpp"
#include "reports/study_data.hpp"

namespace seedcal::reports {

// The report's content; sections appear only when the study has their data.
Document build_report(const StudyData& study);

// Gives every table and plot a distinct id (a repeated one gets "_2", "_3", ...).
void make_ids_unique(Document& doc);

// Writes report.html, report.md and DIR/report/*; returns the paths written. Throws InputError
// when DIR holds no study, RunFailed when a file cannot be written.
std::vector<std::string> write_report(const Document& doc, const std::string& dir);

// load_study + build_report + write_report.
std::vector<std::string> render_report(const std::string& dir);

}  // namespace seedcal::reports
