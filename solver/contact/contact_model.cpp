#include "solver/contact/contact_model.hpp"

namespace seedcal {

const char* to_string(NormalModel m) { return m == NormalModel::hmnr ? "hmnr" : "hertz_mindlin"; }

const char* to_string(RollingModel m) {
  switch (m) {
    case RollingModel::cdt: return "cdt";
    case RollingModel::epsd: return "epsd";
    default: return "none";
  }
}

bool parse_normal_model(std::string_view s, NormalModel& out) {
  if (s == "hertz_mindlin") { out = NormalModel::hertz_mindlin; return true; }
  if (s == "hmnr") { out = NormalModel::hmnr; return true; }
  return false;
}

bool parse_rolling_model(std::string_view s, RollingModel& out) {
  if (s == "none") { out = RollingModel::none; return true; }
  if (s == "cdt") { out = RollingModel::cdt; return true; }
  if (s == "epsd") { out = RollingModel::epsd; return true; }
  return false;
}

}  // namespace seedcal
