#pragma once
// A finished study directory read back for export: DIR/summary.json says what the study settled on
// (the calibrated and held values, the chosen clump model, the study's recorded text and file);
// the study's own scene, with that model's and test's overrides and those values applied, gives the
// rest, read as a run of that scene reads it.
#include <string>

#include "calibrate/export/exported_model.hpp"

namespace seedcal {

struct FinishedStudyOptions {
  std::string study_dir;   // holds summary.json (seedcal calibrate --out)
  // The study file, when it is no longer where summary.json's provenance.study_file names it (that
  // path is as it was given to `seedcal calibrate`, so relative to where it ran). Empty: that one.
  std::string study_file;
  // The test ([[target]] or [[verify.test]] name) whose scene supplies the materials, interactions
  // and contact model. Empty: the first target, the scene the values were calibrated in.
  std::string test;
};

// Throws InputError naming the file, the key, the value and what is allowed when the directory holds
// no finished study, the study's files changed since it ran (their fingerprint differs from the
// recorded one), or its scene has no seed.
ExportedModel read_finished_study(const FinishedStudyOptions& options);

}  // namespace seedcal
