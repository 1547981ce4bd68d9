#pragma once
// The [output] table every scene config accepts: files a run writes on request besides its
// metrics, CSV and picture (docs/scenes/README.md, "Trajectories"):
//   [output] trajectory = false, trajectory_interval_s = 0.01
#include "calibrate/config/toml_reader.hpp"

namespace seedcal {

struct OutputConfig {
  bool trajectory = false;              // DIR/trajectory.h5 + DIR/trajectory.xdmf
  double trajectory_interval_s = 0.01;  // simulated time between frames
};

// Reads [output] when present (an absent table means the defaults).
OutputConfig read_output(TomlReader& root);

}  // namespace seedcal
