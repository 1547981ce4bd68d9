#include "calibrate/config/output_config.hpp"

namespace seedcal {

OutputConfig read_output(TomlReader& root) {
  OutputConfig c;
  if (auto out = root.table("output")) {
    c.trajectory = out->boolean("trajectory", false);
    c.trajectory_interval_s = out->number("trajectory_interval_s", Range::left_open(0.0, 1e3), 0.01);
    out->check_unknown_keys();
  }
  return c;
}

}  // namespace seedcal
