#pragma once
// Everything a report reads from a study directory: the store (DIR/study.h5: header, every DEM
// evaluation, the stages' JSON), DIR/summary.json and the scene outputs under DIR/scenes/.
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "store/study_store.hpp"
#include "store/study_summary.hpp"

namespace seedcal::reports {

struct StudyData {
  std::string dir;
  bool has_store = false;
  StudyHeader header;
  std::vector<EvaluationRecord> evaluations;
  nlohmann::json stages = nlohmann::json::object();
  std::optional<StudySummary> summary;               // unset when there is no readable summary.json
  std::vector<std::string> problems;                  // what could not be read (shown in the report)

  // The stage's JSON, or nullptr when the store has no such stage.
  const nlohmann::json* stage(const std::string& name) const;
  // The highest N of the "solve_round_N" stages (0: none).
  int last_solve_round() const;
};

// Reads DIR/study.h5 and DIR/summary.json. Throws InputError when DIR has neither, RunFailed when
// the store is unreadable (StudyStore::open); an unreadable summary.json is a problem, not an error.
StudyData load_study(const std::string& dir);

}  // namespace seedcal::reports
