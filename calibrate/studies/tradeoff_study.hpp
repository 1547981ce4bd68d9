#pragma once
// Speed against accuracy (`seedcal study tradeoff`, docs/studies.md): one scene's index at several
// time-step fractions (0.05 to 0.4 of the Rayleigh step) and at several seed Young's moduli (the
// common speed-up of a softer particle: the Rayleigh step grows like E^-1/2, so 165 MPa -> 1.65 MPa
// takes a ten times longer step), with the same seeds in every row so that the differences are
// the setting's. Each row: the index (mean, sd, samples), its change against the sweep's
// reference row (the smallest fraction; the stiffest modulus), whether that change exceeds two
// pooled standard errors, CPU seconds and steps per run and the speed-up against the reference.
// Per sweep, the cheapest row whose change stays within the tolerance is named, so a user can pick
// a cheaper setting knowing what it costs.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "calibrate/studies/study_progress.hpp"

namespace seedcal {

struct TradeoffOptions {
  std::string scene;                  // a scene file
  std::string metric;                 // index key of metrics.json; empty: the scene's own index
  std::vector<std::string> sets;      // overrides for every row (e.g. fidelity=quick)
  std::vector<double> rayleigh_fractions = {0.05, 0.1, 0.2, 0.3, 0.4};
  std::vector<double> youngs_moduli_pa = {1.65e8, 1.65e7, 1.65e6};
  std::string material = "seed";      // whose Young's modulus the second sweep changes
  double tolerance = 0.05;            // relative change a user accepts
  int repeats = 3;                    // seeds seed, seed + 1, ... in every row
  int threads = 1;
  int jobs = 1;                       // a row's repeats at once (one thread each when > 1)
  std::uint64_t seed = 1;
  std::string out_dir;                // scenes write their CSV and pictures below it
  StudyProgress* progress = nullptr;  // told of every row's runs (optional)
};

nlohmann::json tradeoff_study(const TradeoffOptions& o);
// Its DEM runs, row by row (the modulus sweep's row at the scene's own step and modulus, which
// reuses the step sweep's runs, included: a plan before any run cannot know it is reused).
std::vector<PlannedRuns> tradeoff_plan(const TradeoffOptions& o);

// The rows of both sweeps as CSV (header first).
std::string tradeoff_csv(const nlohmann::json& study);

}  // namespace seedcal
