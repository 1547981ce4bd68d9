#pragma once
// A study's summary (DIR/summary.json, docs/store.md "summary.json"): what the calibration found,
// what it cost and where it came from. The pipeline fills a StudySummary; `to_json` here is the one
// place its JSON is written, and `summary_from_json` the one place it is read back (reports,
// export). The stages' own reports (the solve, the posterior, the curve pick, the verification and
// the model choice) are carried as the JSON documents their stages wrote: their layout is the
// stage's (docs/calibrate.md) and lives in study.h5 (/stages) as well.
#include <array>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace seedcal {

// One target confirmed at the calibrated point (confirm_stage.cpp): every finished replicate and,
// when at least two finished, their statistics.
struct ConfirmedStats {
  double mean = 0.0, sd = 0.0, cv = 0.0;
  double rel_error = 0.0;                 // mean / target - 1
  std::array<double, 2> rel_error_ci{};   // its two-sided interval (Student t)
  double confidence = 0.0;                // of that interval
  bool within_tolerance = false;          // |rel_error| <= tolerance
  bool resolved = false;                  // the whole interval within +-tolerance
  bool significant_miss = false;          // the interval excludes zero
  long replicates_to_resolve_tolerance = 0;  // n >= (t sd / (tolerance |target|))^2
};

struct ConfirmedTarget {
  double target = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> samples;            // the finished replicates' metric
  std::vector<std::uint64_t> seeds;       // their seeds
  std::optional<ConfirmedStats> stats;    // unset: fewer than two finished
  std::string note;                       // why there are no statistics
};

// Parameter path -> value, and -> 95 % credible interval.
using ParameterValues = std::map<std::string, double>;
using ParameterIntervals = std::map<std::string, std::array<double, 2>>;

// [verify] calibrate_each_model: one model's own calibration.
struct ModelCalibration {
  std::string model, stage_prefix;
  bool calibrated_yet = false;  // the fields below hold a result
  ParameterValues calibrated;
  bool converged = false;
  std::map<std::string, ConfirmedTarget> confirmed;
  int evaluations = -1;
  std::optional<ParameterIntervals> calibrated_interval;
  std::optional<std::map<std::string, bool>> identified;
  nlohmann::json curve_picked;  // null: no point picked on its curve
};

struct SummaryProvenance {
  std::string seedcal_version, study_file, config_hash, config;
  std::uint64_t seed = 0;
};

struct StudySummary {
  int schema_version = 0;       // the study directory's layout (docs/store.md); 1 when absent
  std::string study, stage_reached;
  ParameterValues calibrated, held_at_nominal;
  std::map<std::string, double> targets;                 // metric -> target value
  std::map<std::string, ConfirmedTarget> confirmed;      // metric -> the last confirmation round
  bool converged = false;
  int confirmation_rounds = 0;
  int evaluations = 0;                       // DEM runs of the calibration (stages 1-5)
  int evaluations_total = 0;                 // with the verification
  int evaluations_from_store = 0;            // of which answered from the store
  int classical_workflow_evaluations = 0;    // PB + path + CCD, 3 replicates, + 3 confirmations
  double tolerance = std::numeric_limits<double>::quiet_NaN();  // NaN: not recorded
  ParameterIntervals calibrated_interval;
  std::map<std::string, bool> identified;
  std::vector<ModelCalibration> calibration_per_model;  // empty unless every model is calibrated
  double cpu_seconds = 0.0, calibration_cpu_seconds = 0.0, verification_cpu_seconds = 0.0, wall_seconds = 0.0;
  SummaryProvenance provenance;
  // What the scenes said about their rigs before any run (calibrate/pipeline/scene_check.hpp: a
  // box a few seeds across, a specimen under two seeds tall ...), each with its test and model:
  // the results were measured on those rigs.
  std::vector<std::string> warnings;
  // The stages' reports (null: the stage has not reported).
  nlohmann::json solution_set = nlohmann::json::object();  // the solve stage
  nlohmann::json posterior;        // without its region grid (that is in study.h5)
  nlohmann::json curve;            // the pick along the solution curve
  nlohmann::json verification;     // stage 6
  nlohmann::json model_selection;  // stage 7
  nlohmann::json stages = nlohmann::json::object();  // a digest of every stage's design and fits
};

nlohmann::json to_json(const ConfirmedTarget& c);
nlohmann::json to_json(const StudySummary& s);

// Reads a summary.json of this or an older schema (a member it lacks keeps its default). Throws
// InputError naming `file` and the member when one has the wrong type, or when the summary's
// schema_version is newer than this build's.
StudySummary summary_from_json(const nlohmann::json& j, const std::string& file);
// A posterior report's `calibrated_interval` and `identified` (absent: left empty); `where` names
// the report in an error.
void posterior_identification(const nlohmann::json& posterior, const std::string& where, ParameterIntervals* interval,
                              std::map<std::string, bool>* identified);
// Reads and parses FILE (InputError when it cannot be opened or parsed).
StudySummary read_study_summary(const std::string& file);

}  // namespace seedcal
