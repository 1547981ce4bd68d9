#pragma once
// A tiny real study for the report's end-to-end tests: the impact scene (milliseconds a run,
// noise-free), one target (the Hertz contact time) and two calibrated parameters (Young's modulus
// and density: an underdetermined pair, so the solve stage traces a solution curve), a
// verification test with an experiment and one without, and two clump "models" (time steps).
// Every section of the report has data except the scene pictures (the impact scene draws none).
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "tests/support/cli.hpp"

namespace seedcal::testing {

// Runs the study into DIR/out (the report is written by `seedcal calibrate` itself); returns
// DIR/out, or "" after a failed assertion.
inline std::string run_report_study(const std::string& dir) {
  const std::string scene = source_dir() + "/data/scenes/examples/impact.toml";
  char text[4096];
  std::snprintf(text, sizeof text, R"(name = "impact-report"
seed = 7

[[target]]
name = "contact time"
scene = "%s"
set = ["duration_s=1.0e-4", "dt_s=2.0e-8"]
metric = "contact_duration_s"
value = 4.9e-5

[[parameter]]
path = "materials.glass.youngs_modulus_pa"
low = 2.0e10
high = 6.0e10
calibrate = true

[[parameter]]
path = "materials.glass.density_kg_m3"
low = 2000.0
high = 3200.0
calibrate = true

[screen]
runs = 8

[confirm]
replicates = 2
tolerance = 0.01
max_evaluations = 50

[verify]
replicates = 2

[[verify.test]]
name = "peak force"
scene = "%s"
metric = "max_normal_force_n"
value = 3900.0
sd = 100.0

[[verify.test]]
name = "overlap"
scene = "%s"
metric = "max_overlap_m"
replicates = 1

[[model]]
name = "dt-2e-8"
set = ["duration_s=1.0e-4", "dt_s=2.0e-8"]

[[model]]
name = "dt-1e-8"
set = ["duration_s=1.0e-4", "dt_s=1.0e-8"]
)",
                scene.c_str(), scene.c_str(), scene.c_str());
  write_text(dir + "/study.toml", text);
  const auto r = run_cli("calibrate " + dir + "/study.toml --out " + dir + "/out --jobs 2 --threads 1 --quiet");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  return r.exit_code == 0 ? dir + "/out" : std::string();
}

}  // namespace seedcal::testing
