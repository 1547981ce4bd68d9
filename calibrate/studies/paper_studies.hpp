#pragma once
// The paper's section 4 studies (`seedcal study KIND`, docs/studies.md):
//   multicontact: Hertz-Mindlin (HM) vs the multi-contact correction (HMNR) on the free drop
//                 (individual behaviour: rebound height, contact points) and optionally the drum
//                 (assembly behaviour: dynamic angle of repose);
//   stiffness:    the free drop under HMNR at several Young's moduli (contact points fall and the
//                 rebound rises as E increases: the paper's Figure 26);
//   moisture:     Young's modulus against moisture content (Table 3) and the seed's dimensions
//                 after soaking (Table 2), per variety; no DEM.
// Each returns one JSON object (samples, means, sds, the paper's numbers beside them) that the
// command writes to DIR/KIND.json with a CSV of its table.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "calibrate/studies/study_progress.hpp"

namespace seedcal {

struct PaperStudyOptions {
  std::string free_drop_scene;        // a free_drop scene file
  std::string drum_scene;             // a drum scene file (multicontact: empty = no drum runs)
  std::vector<std::string> sets;      // overrides for every scene (e.g. particle.clump_file=...)
  int repeats = 10;                   // free-drop repeats (seeds seed, seed + 1, ...)
  int drum_repeats = 1;
  int threads = 1;
  std::uint64_t seed = 1;
  std::vector<double> youngs_moduli_pa = {1.65e6, 1.65e7, 1.65e8};  // stiffness
  std::string out_dir;                // scenes write their CSV and pictures below it
  StudyProgress* progress = nullptr;  // told of every scene's runs (optional)
};

// Their DEM runs, scene by scene.
std::vector<PlannedRuns> multicontact_plan(const PaperStudyOptions& o);
std::vector<PlannedRuns> stiffness_plan(const PaperStudyOptions& o);

nlohmann::json multicontact_study(const PaperStudyOptions& o);
nlohmann::json stiffness_study(const PaperStudyOptions& o);
// `variety`: a name under data/varieties/ or a file path.
nlohmann::json moisture_study(const std::string& variety);

// The rows of a study's table as CSV (header first).
std::string study_csv(const nlohmann::json& study);

}  // namespace seedcal
