#include "calibrate/pipeline/study_trajectories.hpp"

#include <cctype>
#include <cmath>
#include <cstdio>

namespace seedcal {

bool StudyTrajectories::IsValid(std::string* error) const {
  // The range of [output] trajectory_interval_s (calibrate/config/output_config.cpp).
  if (std::isfinite(interval_s) && interval_s > 0.0 && interval_s <= 1e3) return true;
  if (error) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "trajectory interval_s = %g: must be in (0, 1000]", interval_s);
    *error = buf;
  }
  return false;
}

bool parse_study_trajectories(const std::string& stages, StudyTrajectories* out, std::string* error) {
  if (stages.empty() || stages == "verify") {
    out->verify = true;
  } else if (stages == "confirm") {
    out->confirm = true;
  } else if (stages == "all") {
    out->verify = out->confirm = true;
  } else {
    if (error) *error = "--trajectory = \"" + stages + "\": must be verify, confirm or all";
    return false;
  }
  return true;
}

std::string path_slug(const std::string& name) {
  std::string out;
  for (const char c : name) out += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return out.empty() ? std::string("test") : out;
}

}  // namespace seedcal
