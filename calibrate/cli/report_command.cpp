// `seedcal report DIR`: renders the study directory DIR (written by `seedcal calibrate --out DIR`)
// as DIR/report.html, DIR/report.md and DIR/report/*.csv|svg (docs/reports.md). `seedcal
// calibrate` renders the same report at the end of every study; this re-renders it, e.g. after
// an upgrade or for a study that was interrupted.
#include <iostream>

#include "calibrate/cli/commands.hpp"
#include "calibrate/cli/errors.hpp"
#include "reports/report.hpp"

namespace seedcal {

void add_report_command(CLI::App& app, GlobalOptions& g) {
  auto dir = std::make_shared<std::string>();
  CLI::App* sub = app.add_subcommand("report", "render a study directory as report.html, report.md and CSV tables");
  sub->add_option("dir", *dir, "study directory (the --out of `seedcal calibrate`)")->required();
  add_common_options(*sub, g);
  sub->callback([dir] {
    const auto files = reports::render_report(*dir);
    std::cout << *dir << "/report.html\n" << *dir << "/report.md\n"
              << "(" << files.size() << " files written, tables and plots under " << *dir << "/report/)\n";
  });
}

}  // namespace seedcal
