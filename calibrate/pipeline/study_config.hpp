#pragma once
// A calibration study (DESIGN.md, "Calibration pipeline"): the targets (a scene, the metric it
// measures and the measured value), the candidate DEM parameters with their screening ranges, and
// the settings of each stage. Read from a TOML study file; every problem names the file, the line,
// the key, the value and the allowed range (docs/calibrate.md lists the keys).
#include <cstdint>
#include <string>
#include <vector>

#include <toml.hpp>

namespace seedcal {

struct StudyTarget {
  std::string name;              // short label ("shear"); default: the metric
  std::string scene;             // scene file, resolved against the study file's folder
  std::vector<std::string> sets; // overrides applied to the scene before the parameters
  std::string metric;            // key of the scene's metrics.json (e.g. shear_strength_pa)
  double value = 0.0;            // the measured value the study fits
  double weight = 1.0;           // joint mode: weight of this target's squared relative error
  // The experiment's sd (0: not given) and, for a calibration target, how many tests its value
  // is the mean of (the posterior counts sd^2 / lab_repeats as the value's variance). Verification
  // tests also say whether the experiment gave a value at all (without one the test is reported as
  // simulation only).
  double sd = 0.0;
  int lab_repeats = 1;
  bool has_value = true;
  int replicates = 0;            // verification tests: runs per model (0: verify.replicates)
};

// A clump model the study verifies and selects among ([[model]]): overrides applied to every scene
// of the study (e.g. particle.clump_file=...; `clump_model = "manual-7"` adds particle.model=manual-7,
// one of the variety's models; a study-wide `variety` adds variety=FILE first). The first model is
// the one the study calibrates.
struct StudyModel {
  std::string name;
  std::vector<std::string> sets;
};

struct VerifySettings {
  int replicates = 2;            // DEM runs per verification test and model (fresh seeds)
  double error_margin = 0.02;    // selection: cheapest model within this of the lowest mean |error|
  double cost_margin = 0.10;     // ... when it saves at least this fraction of the best's CPU time
  // One target, two kept parameters it does not both identify: the verification test named here
  // (empty: the one that answers most along the curve, curve_stage.cpp) runs at `curve_points`
  // points along the target's solution curve and picks the point there (0: off).
  int curve_points = 4;
  std::string curve_test;
  // Each model calibrated (stages 1-5, posterior, curve) under its own overrides before its
  // verification, instead of every model verified at the first model's values.
  bool calibrate_each_model = false;
};

struct StudyParameter {
  std::string path;              // the --set path (seed_seed.static_friction)
  double low = 0.0, high = 1.0;  // screening range (coded -1 / +1)
  double min = 0.0, max = 0.0;   // hard limits the ascent and the surrogate stay inside
  double nominal = 0.0;          // value used while the parameter is not varied
  double prior = 0.0;            // the choice rule prefers solutions close to this
  bool calibrate = false;        // always kept after screening (the study solves for it)
};

struct ScreenSettings {
  int runs = 12;                 // Plackett-Burman runs: 8, 12, 16, 20 or 24
  int replicates = 1;
  double alpha = 0.10;           // significance level of the effects' t test
};

struct AscentSettings {
  double step = 0.5;             // coded step of the base factor along the path
  int max_steps = 6;
  double box_half_width = 0.5;   // coded half-width of the surrogate box around the crossing
};

struct SurrogateSettings {
  std::string design = "auto";   // auto (CCD for 2 kept factors, Box-Behnken for 3+), ccd, box_behnken
  std::string model = "auto";    // auto (cross-validated choice), quadratic, gp
  int center_points = 2;
  int replicates = 1;
};

struct ConfirmSettings {
  int replicates = 3;            // fresh DEM runs (unused seeds) per confirmation
  double tolerance = 0.02;       // relative error accepted
  double confidence = 0.95;      // of the stated bound on the relative error
  int batch = 2;                 // acquisition-chosen points added per infill round
  int max_evaluations = 46;      // DEM runs of the whole study (every replicate counts)
  int max_rounds = 6;
  // Keep the point while no target's confidence interval excludes zero (more replicates there)
  // instead of refitting and moving on every miss (confirm_stage.cpp).
  bool hold_unless_significant = true;
};

struct StudyConfig {
  std::string file;              // as given
  std::string dir;               // its folder (relative paths resolve here)
  std::string variety_file;      // the study-wide `variety` (absolute), "" when it names none
  std::string name;
  std::uint64_t seed = 1;
  std::vector<StudyTarget> targets;
  std::vector<StudyParameter> parameters;
  ScreenSettings screen;
  AscentSettings ascent;
  SurrogateSettings surrogate;
  ConfirmSettings confirm;
  std::vector<StudyTarget> checks;  // stage 6: verification tests at the calibrated values
  std::vector<StudyModel> models;   // stage 7: never empty (one model with no overrides by default)
  VerifySettings verify;
  std::string text;              // the study file after overrides (recorded in the store)
  toml::value doc;

  int index_of(const std::string& path) const;  // -1 when not a parameter
  // Scenes a request can name: the targets (0 .. T-1), then the verification tests (T ..).
  int scene_count() const { return static_cast<int>(targets.size() + checks.size()); }
  const StudyTarget& scene_of(int index) const;
};

// Reads and validates a study file (throws InputError with every problem found).
StudyConfig read_study(const std::string& path, const std::vector<std::string>& sets = {});
// The same from a study's recorded text (the store's config text: the file after the overrides it
// was run with), its relative paths resolved against `path`, the study file's location; s.text is
// `text` itself, so the fingerprint of an unchanged study is the one recorded.
StudyConfig read_study_text(const std::string& text, const std::string& path);

// Fingerprint of everything that decides the study's results: the study text and the text of
// every scene file it names, and of every variety and clump file those scenes use under each model
// (a changed scene, variety or clump refuses --resume as a changed study does).
std::string study_fingerprint(const StudyConfig& s);
// The fingerprint under the older rule: each file named as the study's paths spelt it from the
// working directory the study was started in. A store fingerprinted by that rule is accepted on
// resume when this matches (run_study.cpp) and then takes the current fingerprint.
std::string study_fingerprint_as_spelt(const StudyConfig& s);

}  // namespace seedcal
