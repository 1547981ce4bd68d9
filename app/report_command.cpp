// `seedcal report DIR`: renders the study directory DIR (written by `seedcal calibrate --out DIR`)
// as DIR/report.html, DIR/report.md and DIR/report/*.csv|svg (docs/reports.md). `seedcal
// calibrate` renders the same report at the end of every study; this re-renders it, e.g. after
// an upgrade or for a study that was interrupted. A directory written by `seedcal study` (no
// study store, but KIND.json files) gets the studies report (reports/studies_report.hpp).
#include <iostream>

#include "app/commands.hpp"
#include "store/errors.hpp"
#include <filesystem>

#include "reports/report.hpp"
#include "reports/studies_report.hpp"

namespace seedcal {

void add_report_command(CLI::App& app, GlobalOptions& g) {
  auto dir = std::make_shared<std::string>();
  CLI::App* sub = app.add_subcommand("report", "render a study directory as report.html, report.md and CSV tables");
  sub->add_option("dir", *dir, "study directory (the --out of `seedcal calibrate` or `seedcal study`)")->required();
  add_common_options(*sub, g);
  sub->callback([dir] {
    namespace fs = std::filesystem;
    const bool calibration = fs::exists(*dir + "/study.h5") || fs::exists(*dir + "/summary.json");
    const auto files = !calibration && !reports::study_outputs(*dir).empty() ? reports::render_studies_report(*dir)
                                                                              : reports::render_report(*dir);
    std::cout << *dir << "/report.html\n" << *dir << "/report.md\n"
              << "(" << files.size() << " files written, tables and plots under " << *dir << "/report/)\n";
  });
}

}  // namespace seedcal
