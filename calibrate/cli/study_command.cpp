// `seedcal study`: see DESIGN.md ("Interface").
#include "calibrate/cli/commands.hpp"
#include "calibrate/cli/errors.hpp"

namespace seedcal {

void add_study_command(CLI::App& app, GlobalOptions& g) {
  CLI::App* sub = app.add_subcommand("study", "(study: not available in this build yet)");
  add_common_options(*sub, g);
  sub->allow_extras();
  sub->callback([] { throw RunFailed("'seedcal study' is not available in this build yet"); });
}

}  // namespace seedcal
