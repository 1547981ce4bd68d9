#pragma once
// The calibration pipeline (DESIGN.md, "Calibration pipeline"; docs/calibrate.md): screen ->
// steepest ascent -> surrogate -> solve -> confirm (with infill). Each stage reads what the ones
// before it decided from PipelineState, plans its DEM runs through the StudyEvaluator (which
// answers finished runs from the store), and records its design and fits in the store.
#include <algorithm>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "calibrate/pipeline/study_evaluator.hpp"
#include "doe/rsm/level_curve.hpp"
#include "doe/surrogate/gaussian_process.hpp"
#include "store/study_summary.hpp"

namespace seedcal {

struct PipelineState {
  // The model this state calibrates (StudyConfig::models; 0 unless [verify] calibrate_each_model),
  // the prefix of its stages' names in the store ("" for the first model) and the DEM runs made
  // before its calibration began (its budget counts its own runs).
  int model = 0;
  std::string stage_prefix;
  int runs_before = 0;
  std::vector<int> kept;            // study parameter indices the later stages vary
  Eigen::VectorXd nominal;          // natural values of every parameter (held when not kept)
  Eigen::VectorXd first_order;      // screening: coded first-order coefficients of the kept factors
  double screen_mean = 0.0;         // screening: mean response of the primary target
  // Per target: lower 95 % bound of the run-to-run noise variance the screening measured (0 when
  // it had no error estimate, e.g. a deterministic scene); floors the GP's noise.
  std::vector<double> run_noise_var_floor;
  // The surrogate box in natural units, one row per kept factor.
  Eigen::VectorXd box_lo, box_hi;
  std::string surrogate_kind;       // per primary target: "quadratic" or "gp"
  Eigen::VectorXd chosen;           // natural, every parameter
  nlohmann::json solution;          // the solve stage's report
  std::map<std::string, ConfirmedTarget> confirmed;  // metric -> the last confirmation round
  nlohmann::json posterior;         // after confirmation: intervals and identification (posterior_stage.cpp)
  Eigen::VectorXd posterior_lo_coded, posterior_hi_coded;  // its 95 % intervals, box-coded
  // The pick along the solution curve (curve_stage.cpp). The curve: one target's level set through
  // the confirmed point, box-coded, traced by the posterior stage on its refitted surrogate (not
  // usable when that surrogate misses the target everywhere in the box).
  doe::CurvePath curve_path;
  std::string curve_mode;           // "curve" (a line along it) or "region" (a plane over the box)
  int curve_scene = -1;             // the verification test run there (StudyConfig::scene_of); -1: none
  Eigen::VectorXd curve_beta;       // that test's response model (curve_features) ...
  Eigen::MatrixXd curve_cov;        // ... and the covariance of its coefficients, as the posterior counts it
  int curve_df = 0;                 // the residual degrees of freedom
  nlohmann::json curve;             // the stage's report
  nlohmann::json curve_verification;  // that test's verification under the first model, from the curve's runs
  bool converged = false;
  int rounds = 0;
  int calibration_runs = -1;        // DEM runs of stages 1-5 (set when confirmation ends)
  nlohmann::json verification;      // stage 6: the chosen model's tests
  nlohmann::json selection;         // stage 7: every model, the Pareto front and the choice

  bool is_kept(int parameter) const { return std::find(kept.begin(), kept.end(), parameter) != kept.end(); }
};

// Index of the target that drives the one-target stages (ascent): the largest weight, first wins.
int primary_target(const StudyConfig& s);

// Natural value of every parameter from the kept factors' values (others at nominal).
Eigen::VectorXd full_point(const PipelineState& st, const Eigen::VectorXd& kept_values);

// Mean response per target at each requested point: runs is requests in plan order (targets
// inside replicates, as StudyEvaluator::plan makes them); NaN where every replicate failed.
Eigen::MatrixXd mean_responses(const StudyConfig& s, const std::vector<EvaluationRecord>& records, int points,
                               int replicates);

// The response-surface design (coded -1 .. 1) for k kept factors: five levels for one, a
// face-centred CCD for two (or when the study asks for "ccd"), Box-Behnken for 3 to 7; `name`
// (optional) receives the design's name.
Eigen::MatrixXd surrogate_design(const StudyConfig& s, int k, std::string* name = nullptr);

nlohmann::json run_screening(StudyEvaluator& ev, PipelineState& st, StudyStore& store);
nlohmann::json run_ascent(StudyEvaluator& ev, PipelineState& st, StudyStore& store);
nlohmann::json run_surrogate_design(StudyEvaluator& ev, PipelineState& st, StudyStore& store);
// Every finished run of `target` on the kept subspace (held parameters at nominal) inside the
// surrogate box, in box-coded units (-1 .. 1 per kept factor).
void gather_surrogate_data(const StudyEvaluator& ev, const PipelineState& st, int target, Eigen::MatrixXd* U,
                           Eigen::VectorXd* y);
// Natural values of the kept factors at box-coded u.
Eigen::VectorXd box_point(const PipelineState& st, const Eigen::VectorXd& u);
// The other way: the kept factors of `natural` (one value per study parameter), box-coded and
// clamped to the box.
Eigen::VectorXd box_coded(const PipelineState& st, const Eigen::VectorXd& natural);
// Fits the surrogates to every record on the kept subspace and solves for the target(s).
nlohmann::json fit_and_solve(StudyEvaluator& ev, PipelineState& st, StudyStore& store, const std::string& label);
// Confirms at st.chosen; while not converged and the budget allows, adds infill points and
// re-solves.
nlohmann::json run_confirmation(StudyEvaluator& ev, PipelineState& st, StudyStore& store);
// After confirmation: the posterior of the kept parameters over the surrogate box, their 95 %
// credible intervals and whether each is identified (posterior_stage.cpp; docs/calibrate.md).
nlohmann::json run_posterior(const StudyEvaluator& ev, PipelineState& st, StudyStore& store);
// The posterior's `at_edge` flags for st.chosen as it is now (after the pick has moved), without
// taking the posterior again.
void refresh_edge_flags(const StudyConfig& s, PipelineState& st, StudyStore& store);
// After the posterior, when one target leaves two kept parameters not both identified: a
// verification test (the study's `curve_test`, else the one that answers most between the design's
// ends) runs at points along the target's solution curve, or at the box's corners when it has none;
// the line (or plane) fitted to its response picks the point where it meets the test's experiment
// and sets st.chosen there. Its runs count as that test's verification under st's model
// (curve_stage.cpp; docs/calibrate.md, "The point on the curve"). The report says why when it does not apply.
nlohmann::json run_curve_pick(StudyEvaluator& ev, PipelineState& st, StudyStore& store, const std::string& out_dir);
// The verification tests (StudyConfig::scene_of) that can pick the point: the study's curve_test,
// else those with an experimental value, and of them the ones with a laboratory sd when any has
// one (their answers along the curve are then compared in sd).
std::vector<int> curve_candidates(const StudyConfig& s);
// After the posterior has been taken with the curve test: a picked point outside the 95 %
// highest-density region the target and the test give together (a line extrapolated beyond
// where the data reach) is among the values the data favour least, so the calibrated point
// becomes the posterior's median (its mode when the median lies outside the region too), and the
// test's verification from the curve's runs is read there. Returns the report's entry (null
// when the pick stays); the curve stage's report keeps the line's or plane's own pick.
nlohmann::json keep_pick_in_posterior(const StudyConfig& s, PipelineState& st, StudyStore& store);
// The terms of the curve test's response model at box-coded u: (1, s) with s the arc length of
// u's projection onto the curve, or (1, u1, u2); and the model's mean and the variance of that mean.
Eigen::VectorXd curve_features(const PipelineState& st, const Eigen::VectorXd& u);
doe::GpPrediction curve_prediction(const PipelineState& st, const Eigen::VectorXd& u);
// Stages 6 and 7: every verification test (and the targets) under every model at st.chosen, then
// the model choice by accuracy per CPU second (verify_stage.cpp); pictures under out_dir/scenes/.
// All runs form one batch in model order; whenever the first k < models models have every run,
// st holds the partial selection over them and `on_model_done` (if set) is called with k.
// With `calibrated` (one state per model, [verify] calibrate_each_model; entry 0 is st), each model
// is verified at its own calibrated point and its own curve's runs serve its curve test.
nlohmann::json run_verification(StudyEvaluator& ev, PipelineState& st, StudyStore& store, const std::string& out_dir,
                                const std::function<void(int models_done)>& on_model_done = {},
                                const std::vector<const PipelineState*>& calibrated = {});

}  // namespace seedcal
