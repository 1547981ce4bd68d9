// `seedcal report`: see DESIGN.md ("Interface").
#include "calibrate/cli/commands.hpp"
#include "calibrate/cli/errors.hpp"

namespace seedcal {

void add_report_command(CLI::App& app, GlobalOptions& g) {
  CLI::App* sub = app.add_subcommand("report", "(report: not available in this build yet)");
  add_common_options(*sub, g);
  sub->allow_extras();
  sub->callback([] { throw RunFailed("'seedcal report' is not available in this build yet"); });
}

}  // namespace seedcal
