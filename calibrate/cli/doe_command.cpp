// `seedcal doe`: see DESIGN.md ("Interface").
#include "calibrate/cli/commands.hpp"
#include "calibrate/cli/errors.hpp"

namespace seedcal {

void add_doe_command(CLI::App& app, GlobalOptions& g) {
  CLI::App* sub = app.add_subcommand("doe", "(doe: not available in this build yet)");
  add_common_options(*sub, g);
  sub->allow_extras();
  sub->callback([] { throw RunFailed("'seedcal doe' is not available in this build yet"); });
}

}  // namespace seedcal
