#pragma once
// Before a study runs anything: every scene it will run (each target and verification test under
// each clump model, with the study's overrides and its parameters at their nominal values and at
// their limits) is read and validated as a run would read it. A misspelt override, a missing clump
// file or a parameter range the scene does not allow is bad input (InputError, exit 2) naming the
// study, the test, the model and the scene's own message, not a failure of every DEM run.
#include <string>
#include <vector>

#include "calibrate/pipeline/study_config.hpp"

namespace seedcal {

// Returns the scenes' warnings (each once, with the test and model it was first seen under).
std::vector<std::string> check_study_scenes(const StudyConfig& s);

}  // namespace seedcal
