#include "reports/study_data.hpp"

#include <algorithm>
#include <filesystem>

#include "store/errors.hpp"

namespace seedcal::reports {

const nlohmann::json* StudyData::stage(const std::string& name) const {
  const auto it = stages.find(name);
  return it == stages.end() || it->is_null() ? nullptr : &*it;
}

int StudyData::last_solve_round() const {
  int last = 0;
  const std::string prefix = "solve_round_";
  for (const auto& [key, value] : stages.items()) {
    if (key.rfind(prefix, 0) != 0) continue;
    try {
      last = std::max(last, std::stoi(key.substr(prefix.size())));
    } catch (const std::exception&) {
      // not a round number: not a solve stage
    }
  }
  return last;
}

StudyData load_study(const std::string& dir) {
  namespace fs = std::filesystem;
  StudyData d;
  d.dir = dir;
  const std::string store = dir + "/study.h5", summary = dir + "/summary.json";
  if (!fs::is_directory(dir)) throw InputError(dir + ": not a directory (give the --out directory of `seedcal calibrate`)");
  if (!fs::exists(store) && !fs::exists(summary))
    throw InputError(dir + ": neither study.h5 nor summary.json is here (give the --out directory of `seedcal calibrate`)");
  if (fs::exists(store)) {
    const StudyStore s = StudyStore::open(store);
    d.has_store = true;
    d.header = s.header();
    d.evaluations = s.evaluations();
    d.stages = s.stages();
  } else {
    d.problems.push_back(store + " is missing: only summary.json is reported");
  }
  if (fs::exists(summary)) {
    try {
      d.summary = read_study_summary(summary);
    } catch (const InputError& e) {
      d.problems.push_back(std::string(e.what()) + ": left out");
    }
  }
  return d;
}

}  // namespace seedcal::reports
