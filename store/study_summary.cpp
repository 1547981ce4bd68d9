#include "store/study_summary.hpp"

#include <fstream>
#include <sstream>
#include <type_traits>

#include "store/errors.hpp"
#include "store/study_store.hpp"

namespace seedcal {
namespace {

using nlohmann::json;

json values_json(const ParameterValues& v) {
  json j = json::object();
  for (const auto& [path, x] : v) j[path] = x;
  return j;
}

json intervals_json(const ParameterIntervals& v) {
  json j = json::object();
  for (const auto& [path, iv] : v) j[path] = {iv[0], iv[1]};
  return j;
}

json flags_json(const std::map<std::string, bool>& v) {
  json j = json::object();
  for (const auto& [path, b] : v) j[path] = b;
  return j;
}

json confirmed_json(const std::map<std::string, ConfirmedTarget>& v) {
  json j = json::object();
  for (const auto& [metric, c] : v) j[metric] = to_json(c);
  return j;
}

// Reading: every member is optional (an older summary lacks some); one that is there must have
// its type, else the error names the file and the member's dotted path.
class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void wrong(const std::string& path, const char* want) const {
    throw InputError(file_ + ": " + path + " is not " + want + " (a summary.json of `seedcal calibrate` has it so)");
  }
  // NaN is written as null (JSON has no NaN): a null number reads back as NaN.
  double number(const json& v, const std::string& path) const {
    if (v.is_null()) return std::numeric_limits<double>::quiet_NaN();
    if (!v.is_number()) wrong(path, "a number");
    return v.get<double>();
  }
  template <class T>
  T integer(const json& v, const std::string& path) const {
    if constexpr (std::is_unsigned_v<T>) {
      if (!v.is_number_unsigned()) wrong(path, "a non-negative integer");
    } else if (!v.is_number_integer()) {
      wrong(path, "an integer");
    }
    return v.get<T>();
  }
  bool boolean(const json& v, const std::string& path) const {
    if (!v.is_boolean()) wrong(path, "true or false");
    return v.get<bool>();
  }
  std::string string(const json& v, const std::string& path) const {
    if (!v.is_string()) wrong(path, "a string");
    return v.get<std::string>();
  }
  const json& object(const json& v, const std::string& path) const {
    if (!v.is_object()) wrong(path, "an object");
    return v;
  }
  const json& array(const json& v, const std::string& path) const {
    if (!v.is_array()) wrong(path, "an array");
    return v;
  }
  // Calls f(member, path) when `key` is in j.
  template <class F>
  void with(const json& j, const std::string& at, const char* key, F&& f) const {
    if (j.contains(key)) f(j[key], at.empty() ? std::string(key) : at + "." + key);
  }
  ParameterValues values(const json& v, const std::string& path) const {
    ParameterValues out;
    for (const auto& [k, x] : object(v, path).items()) out[k] = number(x, path + "." + k);
    return out;
  }
  ParameterIntervals intervals(const json& v, const std::string& path) const {
    ParameterIntervals out;
    for (const auto& [k, x] : object(v, path).items()) {
      if (!x.is_array() || x.size() != 2) wrong(path + "." + k, "an array of two numbers");
      out[k] = {number(x[0], path + "." + k + "[0]"), number(x[1], path + "." + k + "[1]")};
    }
    return out;
  }
  std::map<std::string, bool> flags(const json& v, const std::string& path) const {
    std::map<std::string, bool> out;
    for (const auto& [k, x] : object(v, path).items()) out[k] = boolean(x, path + "." + k);
    return out;
  }
  ConfirmedTarget confirmed_target(const json& j, const std::string& at) const {
    object(j, at);
    ConfirmedTarget c;
    with(j, at, "target", [&](const json& v, const std::string& p) { c.target = number(v, p); });
    with(j, at, "samples", [&](const json& v, const std::string& p) {
      for (std::size_t i = 0; i < array(v, p).size(); ++i) c.samples.push_back(number(v[i], p + "[" + std::to_string(i) + "]"));
    });
    with(j, at, "seeds", [&](const json& v, const std::string& p) {
      for (std::size_t i = 0; i < array(v, p).size(); ++i)
        c.seeds.push_back(integer<std::uint64_t>(v[i], p + "[" + std::to_string(i) + "]"));
    });
    with(j, at, "note", [&](const json& v, const std::string& p) { c.note = string(v, p); });
    if (j.contains("mean")) {
      ConfirmedStats s;
      with(j, at, "mean", [&](const json& v, const std::string& p) { s.mean = number(v, p); });
      with(j, at, "sd", [&](const json& v, const std::string& p) { s.sd = number(v, p); });
      with(j, at, "cv", [&](const json& v, const std::string& p) { s.cv = number(v, p); });
      with(j, at, "rel_error", [&](const json& v, const std::string& p) { s.rel_error = number(v, p); });
      with(j, at, "rel_error_ci", [&](const json& v, const std::string& p) {
        if (!v.is_array() || v.size() != 2) wrong(p, "an array of two numbers");
        s.rel_error_ci = {number(v[0], p + "[0]"), number(v[1], p + "[1]")};
      });
      with(j, at, "confidence", [&](const json& v, const std::string& p) { s.confidence = number(v, p); });
      with(j, at, "within_tolerance", [&](const json& v, const std::string& p) { s.within_tolerance = boolean(v, p); });
      with(j, at, "resolved", [&](const json& v, const std::string& p) { s.resolved = boolean(v, p); });
      with(j, at, "significant_miss", [&](const json& v, const std::string& p) { s.significant_miss = boolean(v, p); });
      with(j, at, "replicates_to_resolve_tolerance",
           [&](const json& v, const std::string& p) { s.replicates_to_resolve_tolerance = integer<long>(v, p); });
      c.stats = s;
    }
    return c;
  }
  std::map<std::string, ConfirmedTarget> confirmed(const json& v, const std::string& path) const {
    std::map<std::string, ConfirmedTarget> out;
    for (const auto& [k, x] : object(v, path).items()) out[k] = confirmed_target(x, path + "." + k);
    return out;
  }

 private:
  std::string file_;
};

}  // namespace

json to_json(const ConfirmedTarget& c) {
  json j = {{"samples", c.samples}, {"seeds", c.seeds}, {"n", c.samples.size()}, {"target", c.target}};
  if (!c.note.empty()) j["note"] = c.note;
  if (c.stats) {
    const ConfirmedStats& s = *c.stats;
    j["replicates_to_resolve_tolerance"] = s.replicates_to_resolve_tolerance;
    j["cv"] = s.cv;
    j["mean"] = s.mean;
    j["sd"] = s.sd;
    j["rel_error"] = s.rel_error;
    j["rel_error_ci"] = {s.rel_error_ci[0], s.rel_error_ci[1]};
    j["confidence"] = s.confidence;
    j["within_tolerance"] = s.within_tolerance;
    j["resolved"] = s.resolved;
    j["significant_miss"] = s.significant_miss;
  }
  return j;
}

json to_json(const StudySummary& s) {
  json j;
  j["schema_version"] = s.schema_version;
  j["study"] = s.study;
  j["stage_reached"] = s.stage_reached;
  j["calibrated"] = values_json(s.calibrated);
  j["held_at_nominal"] = values_json(s.held_at_nominal);
  json targets = json::object();
  for (const auto& [metric, v] : s.targets) targets[metric] = v;
  j["targets"] = targets;
  j["confirmed"] = confirmed_json(s.confirmed);
  j["converged"] = s.converged;
  j["confirmation_rounds"] = s.confirmation_rounds;
  j["evaluations"] = s.evaluations;
  j["evaluations_total"] = s.evaluations_total;
  j["evaluations_from_store"] = s.evaluations_from_store;
  j["classical_workflow_evaluations"] = s.classical_workflow_evaluations;
  j["solution_set"] = s.solution_set.is_null() ? json::object() : s.solution_set;
  j["calibrated_interval"] = intervals_json(s.calibrated_interval);
  j["identified"] = flags_json(s.identified);
  if (!s.posterior.is_null()) j["posterior"] = s.posterior;
  if (!s.curve.is_null()) j["curve"] = s.curve;
  if (!s.calibration_per_model.empty()) {
    json per = json::array();
    for (const ModelCalibration& m : s.calibration_per_model) {
      json e = {{"model", m.model}, {"stage_prefix", m.stage_prefix}};
      if (m.calibrated_yet) {
        e["calibrated"] = values_json(m.calibrated);
        e["converged"] = m.converged;
        e["confirmed"] = confirmed_json(m.confirmed);
        e["evaluations"] = m.evaluations;
      }
      if (m.calibrated_interval) e["calibrated_interval"] = intervals_json(*m.calibrated_interval);
      if (m.identified) e["identified"] = flags_json(*m.identified);
      if (!m.curve_picked.is_null()) e["curve_picked"] = m.curve_picked;
      per.push_back(e);
    }
    j["calibration_per_model"] = per;
  }
  j["tolerance"] = s.tolerance;
  if (!s.verification.is_null()) j["verification"] = s.verification;
  if (!s.model_selection.is_null()) j["model_selection"] = s.model_selection;
  j["stages"] = s.stages;
  j["cpu_seconds"] = s.cpu_seconds;
  j["calibration_cpu_seconds"] = s.calibration_cpu_seconds;
  j["verification_cpu_seconds"] = s.verification_cpu_seconds;
  j["wall_seconds"] = s.wall_seconds;
  j["provenance"] = {{"seedcal_version", s.provenance.seedcal_version}, {"study_file", s.provenance.study_file},
                     {"seed", s.provenance.seed}, {"config_hash", s.provenance.config_hash},
                     {"config", s.provenance.config}};
  j["warnings"] = s.warnings;
  return j;
}

StudySummary summary_from_json(const json& j, const std::string& file) {
  const Reader r(file);
  r.object(j, "the document");
  StudySummary s;
  s.schema_version = 1;  // the first summaries had no schema_version
  r.with(j, "", "schema_version", [&](const json& v, const std::string& p) { s.schema_version = r.integer<int>(v, p); });
  if (s.schema_version > kStudyStoreSchemaVersion)
    throw InputError(file + ": schema_version = " + std::to_string(s.schema_version) + ": written by a newer seedcal (this build reads up to " +
                     std::to_string(kStudyStoreSchemaVersion) + ")");
  r.with(j, "", "study", [&](const json& v, const std::string& p) { s.study = r.string(v, p); });
  r.with(j, "", "stage_reached", [&](const json& v, const std::string& p) { s.stage_reached = r.string(v, p); });
  r.with(j, "", "calibrated", [&](const json& v, const std::string& p) { s.calibrated = r.values(v, p); });
  r.with(j, "", "held_at_nominal", [&](const json& v, const std::string& p) { s.held_at_nominal = r.values(v, p); });
  r.with(j, "", "targets", [&](const json& v, const std::string& p) { s.targets = r.values(v, p); });
  r.with(j, "", "confirmed", [&](const json& v, const std::string& p) { s.confirmed = r.confirmed(v, p); });
  r.with(j, "", "converged", [&](const json& v, const std::string& p) { s.converged = r.boolean(v, p); });
  r.with(j, "", "confirmation_rounds", [&](const json& v, const std::string& p) { s.confirmation_rounds = r.integer<int>(v, p); });
  r.with(j, "", "evaluations", [&](const json& v, const std::string& p) { s.evaluations = r.integer<int>(v, p); });
  r.with(j, "", "evaluations_total", [&](const json& v, const std::string& p) { s.evaluations_total = r.integer<int>(v, p); });
  r.with(j, "", "evaluations_from_store",
         [&](const json& v, const std::string& p) { s.evaluations_from_store = r.integer<int>(v, p); });
  r.with(j, "", "classical_workflow_evaluations",
         [&](const json& v, const std::string& p) { s.classical_workflow_evaluations = r.integer<int>(v, p); });
  r.with(j, "", "tolerance", [&](const json& v, const std::string& p) { s.tolerance = r.number(v, p); });
  r.with(j, "", "calibrated_interval", [&](const json& v, const std::string& p) { s.calibrated_interval = r.intervals(v, p); });
  r.with(j, "", "identified", [&](const json& v, const std::string& p) { s.identified = r.flags(v, p); });
  r.with(j, "", "calibration_per_model", [&](const json& v, const std::string& p) {
    for (std::size_t i = 0; i < r.array(v, p).size(); ++i) {
      const std::string at = p + "[" + std::to_string(i) + "]";
      const json& e = r.object(v[i], at);
      ModelCalibration m;
      r.with(e, at, "model", [&](const json& x, const std::string& q) { m.model = r.string(x, q); });
      r.with(e, at, "stage_prefix", [&](const json& x, const std::string& q) { m.stage_prefix = r.string(x, q); });
      m.calibrated_yet = e.contains("calibrated");
      r.with(e, at, "calibrated", [&](const json& x, const std::string& q) { m.calibrated = r.values(x, q); });
      r.with(e, at, "converged", [&](const json& x, const std::string& q) { m.converged = r.boolean(x, q); });
      r.with(e, at, "confirmed", [&](const json& x, const std::string& q) { m.confirmed = r.confirmed(x, q); });
      r.with(e, at, "evaluations", [&](const json& x, const std::string& q) { m.evaluations = r.integer<int>(x, q); });
      r.with(e, at, "calibrated_interval",
             [&](const json& x, const std::string& q) { m.calibrated_interval = r.intervals(x, q); });
      r.with(e, at, "identified", [&](const json& x, const std::string& q) { m.identified = r.flags(x, q); });
      if (e.contains("curve_picked")) m.curve_picked = e["curve_picked"];
      s.calibration_per_model.push_back(std::move(m));
    }
  });
  for (const auto& [key, member] : {std::pair<const char*, double*>{"cpu_seconds", &s.cpu_seconds},
                                    {"calibration_cpu_seconds", &s.calibration_cpu_seconds},
                                    {"verification_cpu_seconds", &s.verification_cpu_seconds},
                                    {"wall_seconds", &s.wall_seconds}}) {
    double* out = member;
    r.with(j, "", key, [&](const json& v, const std::string& p) { *out = r.number(v, p); });
  }
  r.with(j, "", "provenance", [&](const json& v, const std::string& p) {
    r.object(v, p);
    SummaryProvenance& o = s.provenance;
    r.with(v, p, "seedcal_version", [&](const json& x, const std::string& q) { o.seedcal_version = r.string(x, q); });
    r.with(v, p, "study_file", [&](const json& x, const std::string& q) { o.study_file = r.string(x, q); });
    r.with(v, p, "config_hash", [&](const json& x, const std::string& q) { o.config_hash = r.string(x, q); });
    r.with(v, p, "config", [&](const json& x, const std::string& q) { o.config = r.string(x, q); });
    r.with(v, p, "seed", [&](const json& x, const std::string& q) { o.seed = r.integer<std::uint64_t>(x, q); });
  });
  r.with(j, "", "warnings", [&](const json& v, const std::string& p) {
    std::size_t i = 0;
    for (const json& w : r.array(v, p)) s.warnings.push_back(r.string(w, p + "[" + std::to_string(i++) + "]"));
  });
  // The stages' reports, as their stages wrote them.
  r.with(j, "", "solution_set", [&](const json& v, const std::string& p) { s.solution_set = r.object(v, p); });
  r.with(j, "", "posterior", [&](const json& v, const std::string& p) { s.posterior = r.object(v, p); });
  r.with(j, "", "curve", [&](const json& v, const std::string& p) { s.curve = r.object(v, p); });
  r.with(j, "", "verification", [&](const json& v, const std::string& p) { s.verification = r.object(v, p); });
  r.with(j, "", "model_selection", [&](const json& v, const std::string& p) { s.model_selection = r.object(v, p); });
  r.with(j, "", "stages", [&](const json& v, const std::string& p) { s.stages = r.object(v, p); });
  return s;
}

void posterior_identification(const json& posterior, const std::string& where, ParameterIntervals* interval,
                              std::map<std::string, bool>* identified) {
  const Reader r(where);
  r.object(posterior, "the report");
  r.with(posterior, "", "calibrated_interval", [&](const json& v, const std::string& p) { *interval = r.intervals(v, p); });
  r.with(posterior, "", "identified", [&](const json& v, const std::string& p) { *identified = r.flags(v, p); });
}

StudySummary read_study_summary(const std::string& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file + ": cannot open the file (a study directory holds the summary.json that `seedcal calibrate` writes)");
  std::stringstream text;
  text << in.rdbuf();
  json j;
  try {
    j = json::parse(text.str());
  } catch (const json::parse_error& e) {
    throw InputError(file + ": not JSON (" + e.what() + ")");
  }
  return summary_from_json(j, file);
}

}  // namespace seedcal
