#include "calibrate/pipeline/study_config.hpp"

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>

#include "calibrate/clumps/clump_source.hpp"
#include "calibrate/config/variety_scene.hpp"
#include "calibrate/scenes/scene_file.hpp"
#include "calibrate/config/overrides.hpp"
#include "calibrate/config/toml_reader.hpp"
#include "calibrate/pipeline/pipeline.hpp"
#include "store/errors.hpp"
#include "store/study_store.hpp"

namespace seedcal {
namespace {

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// A file the study reads, named relative to the study file's directory (symbolic links and
// ".." resolved), so that the same study started as "data/studies/x.toml" and resumed as
// "/abs/path/data/studies/x.toml", or from another working directory, has one fingerprint.
std::string study_relative_name(const std::string& path, const std::string& study_file) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path base = fs::weakly_canonical(fs::absolute(fs::path(study_file)).parent_path(), ec);
  if (ec) return path;
  const fs::path rel = fs::relative(fs::absolute(fs::path(path)), base, ec);
  return ec || rel.empty() ? path : rel.generic_string();
}

// The keys a target and a verification test share: scene (relative to the study file), set,
// metric and name.
StudyTarget read_scene_metric(TomlReader& t, const StudyConfig& s) {
  StudyTarget x;
  const std::string scene = t.string("scene");
  x.metric = t.string("metric");
  x.name = t.string("name", x.metric);
  if (t.has("set")) x.sets = t.strings("set", 0, 64);
  if (!scene.empty()) {
    x.scene = resolve_data_path(scene, s.file);
    if (!std::filesystem::exists(x.scene)) t.error("scene", "= \"" + scene + "\": no such file");
  }
  return x;
}

void read_target(TomlReader& t, StudyConfig& s) {
  StudyTarget tg = read_scene_metric(t, s);
  tg.value = t.number("value", Range::open(-1e300, 1e300));
  if (t.has("value") && tg.value == 0.0) t.error("value", "= 0: a target must be non-zero (errors are relative)");
  tg.weight = t.number("weight", Range::positive(), 1.0);
  tg.sd = t.number("sd", Range::non_negative(), 0.0);
  tg.lab_repeats = static_cast<int>(t.integer("lab_repeats", 1, 100000, 1));
  if (t.has("lab_repeats") && !t.has("sd")) t.error("lab_repeats", "is given without an sd");
  t.check_unknown_keys();
  s.targets.push_back(std::move(tg));
}

// [[verify.test]]: a scene run at the calibrated values and compared with its experiment.
void read_check(TomlReader& t, StudyConfig& s) {
  StudyTarget c = read_scene_metric(t, s);
  c.has_value = t.has("value");
  c.value = t.number("value", Range::open(-1e300, 1e300), 0.0);
  if (c.has_value && c.value == 0.0) t.error("value", "= 0: an experimental value must be non-zero (errors are relative)");
  c.sd = t.number("sd", Range::non_negative(), 0.0);
  if (t.has("sd") && !c.has_value) t.error("sd", "is given without a value");
  c.replicates = static_cast<int>(t.integer("replicates", 1, 50, 0));
  t.check_unknown_keys();
  for (const auto& q : s.checks)
    if (q.name == c.name) t.error("name", "= \"" + c.name + "\" is used by two verification tests");
  s.checks.push_back(std::move(c));
}

void read_model(TomlReader& t, StudyConfig& s) {
  StudyModel m;
  m.name = t.string("name");
  if (t.has("set")) m.sets = t.strings("set", 0, 64);
  // One of the variety's clump models ([models] of the variety file the scenes or the study name).
  if (t.has("clump_model")) m.sets.insert(m.sets.begin(), "particle.model=" + t.string("clump_model"));
  t.check_unknown_keys();
  for (const auto& q : s.models)
    if (q.name == m.name) t.error("name", "= \"" + m.name + "\" is used by two models");
  s.models.push_back(std::move(m));
}

void read_parameter(TomlReader& t, StudyConfig& s) {
  StudyParameter p;
  p.path = t.string("path");
  p.low = t.number("low", Range());
  p.high = t.number("high", Range());
  if (p.high <= p.low) t.error("high", "must be greater than low (" + std::to_string(p.low) + ")");
  p.min = t.number("min", Range(), p.low);
  p.max = t.number("max", Range(), p.high);
  if (p.min > p.low) t.error("min", "must be at most low (" + std::to_string(p.low) + ")");
  if (p.max < p.high) t.error("max", "must be at least high (" + std::to_string(p.high) + ")");
  p.nominal = t.number("nominal", Range::closed(p.min, p.max), 0.5 * (p.low + p.high));
  p.prior = t.number("prior", Range::closed(p.min, p.max), p.nominal);
  p.calibrate = t.boolean("calibrate", false);
  t.check_unknown_keys();
  for (const auto& q : s.parameters)
    if (q.path == p.path) t.error("path", "= \"" + p.path + "\" is listed twice");
  s.parameters.push_back(std::move(p));
}

}  // namespace

int StudyConfig::index_of(const std::string& path) const {
  for (std::size_t i = 0; i < parameters.size(); ++i)
    if (parameters[i].path == path) return static_cast<int>(i);
  return -1;
}

const StudyTarget& StudyConfig::scene_of(int index) const {
  const auto i = static_cast<std::size_t>(index);
  return i < targets.size() ? targets.at(i) : checks.at(i - targets.size());
}

namespace {

// A study from its parsed document and the text it is recorded (and fingerprinted) as.
StudyConfig read_study_doc(const std::string& path, toml::value doc, std::string text) {
  StudyConfig s;
  s.file = path;
  s.dir = std::filesystem::path(path).parent_path().string();
  s.doc = std::move(doc);
  s.text = std::move(text);
  auto diag = std::make_shared<ConfigDiagnostics>();
  diag->file = path;
  TomlReader root(s.doc, "", diag);
  s.name = root.string("name", std::filesystem::path(path).stem().string());
  s.seed = static_cast<std::uint64_t>(root.integer("seed", 0, (std::int64_t{1} << 40), 1));
  auto targets = root.table_array("target");
  if (targets.empty()) root.error("target", "is required: at least one [[target]] (scene, metric, value)");
  for (auto& t : targets) read_target(t, s);
  auto params = root.table_array("parameter");
  if (params.empty()) root.error("parameter", "is required: at least one [[parameter]] (path, low, high)");
  for (auto& p : params) read_parameter(p, s);
  bool any_calibrated = false;
  for (const auto& p : s.parameters) any_calibrated = any_calibrated || p.calibrate;
  if (!params.empty() && !any_calibrated)
    root.error("parameter", "no parameter has calibrate = true: name what the study solves for");
  if (s.parameters.size() > 23) root.error("parameter", "at most 23 parameters can be screened");

  if (auto t = root.table("screen")) {
    s.screen.runs = static_cast<int>(t->integer("runs", 8, 24, s.screen.runs));
    static const std::set<int> kRuns = {8, 12, 16, 20, 24};
    if (!kRuns.count(s.screen.runs)) t->error("runs", "must be one of 8, 12, 16, 20, 24 (Plackett-Burman sizes)");
    if (static_cast<int>(s.parameters.size()) > s.screen.runs - 1)
      t->error("runs", "must exceed the number of parameters (" + std::to_string(s.parameters.size()) + ")");
    s.screen.replicates = static_cast<int>(t->integer("replicates", 1, 10, s.screen.replicates));
    s.screen.alpha = t->number("alpha", Range::open(0.0, 0.5), s.screen.alpha);
    t->check_unknown_keys();
  }
  if (auto t = root.table("ascent")) {
    s.ascent.step = t->number("step", Range::left_open(0.0, 2.0), s.ascent.step);
    s.ascent.max_steps = static_cast<int>(t->integer("max_steps", 0, 50, s.ascent.max_steps));
    s.ascent.box_half_width = t->number("box_half_width", Range::left_open(0.0, 1.0), s.ascent.box_half_width);
    t->check_unknown_keys();
  }
  if (auto t = root.table("surrogate")) {
    s.surrogate.design = t->choice("design", {"auto", "ccd", "box_behnken"}, s.surrogate.design);
    s.surrogate.model = t->choice("model", {"auto", "quadratic", "gp"}, s.surrogate.model);
    s.surrogate.center_points = static_cast<int>(t->integer("center_points", 1, 10, s.surrogate.center_points));
    s.surrogate.replicates = static_cast<int>(t->integer("replicates", 1, 10, s.surrogate.replicates));
    t->check_unknown_keys();
  }
  if (auto t = root.table("confirm")) {
    s.confirm.replicates = static_cast<int>(t->integer("replicates", 2, 50, s.confirm.replicates));
    s.confirm.tolerance = t->number("tolerance", Range::open(0.0, 1.0), s.confirm.tolerance);
    s.confirm.confidence = t->number("confidence", Range::open(0.5, 1.0), s.confirm.confidence);
    s.confirm.batch = static_cast<int>(t->integer("batch", 0, 32, s.confirm.batch));
    s.confirm.max_evaluations = static_cast<int>(t->integer("max_evaluations", 1, 100000, s.confirm.max_evaluations));
    s.confirm.max_rounds = static_cast<int>(t->integer("max_rounds", 1, 100, s.confirm.max_rounds));
    s.confirm.hold_unless_significant = t->boolean("hold_unless_significant", s.confirm.hold_unless_significant);
    t->check_unknown_keys();
  }
  if (auto t = root.table("verify")) {
    s.verify.replicates = static_cast<int>(t->integer("replicates", 1, 50, s.verify.replicates));
    s.verify.error_margin = t->number("error_margin", Range::closed(0.0, 1.0), s.verify.error_margin);
    s.verify.cost_margin = t->number("cost_margin", Range::closed(0.0, 0.9), s.verify.cost_margin);
    for (auto& c : t->table_array("test")) read_check(c, s);
    // The pick along the solution curve (curve_stage.cpp): 0 turns it off; a line needs at least
    // 3 points for a residual variance.
    const auto points = t->integer("curve_points", 0, 50, s.verify.curve_points);
    if (points == 1 || points == 2) t->error("curve_points", "= " + std::to_string(points) + ": must be 0 (off) or at least 3 (a line and its scatter)");
    s.verify.curve_points = static_cast<int>(points);
    s.verify.curve_test = t->string("curve_test", s.verify.curve_test);
    s.verify.calibrate_each_model = t->boolean("calibrate_each_model", s.verify.calibrate_each_model);
    if (!s.verify.curve_test.empty()) {
      bool found = false;
      std::string names;
      for (const auto& c : s.checks) {
        found = found || c.name == s.verify.curve_test;
        names += (names.empty() ? "" : ", ") + ("\"" + c.name + "\"") + (c.has_value ? "" : " (no value)");
        if (c.name == s.verify.curve_test && !c.has_value)
          t->error("curve_test", "= \"" + s.verify.curve_test + "\": that test has no experimental value to pick a point by");
      }
      if (!found)
        t->error("curve_test", "= \"" + s.verify.curve_test + "\": not one of the [[verify.test]] names (" +
                                   (names.empty() ? std::string("the study has none") : names) + ")");
    }
    t->check_unknown_keys();
  }
  for (auto& m : root.table_array("model")) read_model(m, s);
  if (s.models.empty()) s.models.push_back({"default", {}});
  // A study-wide variety: every scene takes the seed's values from it (variety_scene.hpp), under
  // every model, as if each scene file named it.
  if (root.has("variety")) {
    root.string("variety");  // read here (a string), resolved as a scene's is: relative to this file
    try {
      s.variety_file = std::filesystem::absolute(scene_variety_file(s.doc, path)).lexically_normal().string();
      for (auto& m : s.models) m.sets.insert(m.sets.begin(), "variety=" + s.variety_file);
    } catch (const InputError& e) {
      for (const std::string& problem : e.problems()) root.diagnostics().problems.push_back(problem);
    }
  }
  // The budget must at least pay for screening, the smallest surrogate design (the calibrated
  // parameters only) and one confirmation.
  if (!s.targets.empty() && any_calibrated) {
    int k = 0;
    for (const auto& p : s.parameters) k += p.calibrate ? 1 : 0;
    if (k > 10) root.error("parameter", "at most 10 parameters can have calibrate = true (the surrogate designs go up to 10 factors)");
    const auto design = k > 10 ? 0 : static_cast<int>(surrogate_design(s, k).rows());
    const int nt = static_cast<int>(s.targets.size());
    const int minimum = nt * (s.screen.runs * s.screen.replicates + design * s.surrogate.replicates + s.confirm.replicates);
    if (s.confirm.max_evaluations < minimum) {
      root.error("confirm.max_evaluations", "= " + std::to_string(s.confirm.max_evaluations) + ": too small for this study: "
                    "screening, the smallest surrogate design and one confirmation take " + std::to_string(minimum) +
                    " DEM runs (raise it, or use fewer runs or replicates)");
    }
  }
  root.check_unknown_keys();
  diag->throw_if_any();
  return s;
}

}  // namespace

StudyConfig read_study(const std::string& path, const std::vector<std::string>& sets) {
  toml::value doc = TomlReader::parse_file(path);
  apply_overrides(doc, sets);
  std::string text = toml::format(doc);
  return read_study_doc(path, std::move(doc), std::move(text));
}

StudyConfig read_study_text(const std::string& text, const std::string& path) {
  std::istringstream in(text);
  toml::value doc;
  try {
    doc = toml::parse(in, path);
  } catch (const std::exception& e) {
    throw InputError(path + ": the recorded study text does not parse: " + std::string(e.what()));
  }
  return read_study_doc(path, std::move(doc), text);
}

namespace {

// The fingerprint with each scene, variety and clump file labelled by `name_of` its path.
std::string fingerprint_with(const StudyConfig& s, const std::function<std::string(const std::string&)>& name_of) {
  std::string all = s.text;
  std::set<std::string> clumps;  // the varieties and clump files the scenes use under every model
  for (int i = 0; i < s.scene_count(); ++i) {
    const StudyTarget& t = s.scene_of(i);
    all += "\n--- " + name_of(t.scene) + "\n" + read_text(t.scene);
    for (const auto& m : s.models) {
      try {
        std::vector<std::string> sets = m.sets;
        sets.insert(sets.end(), t.sets.begin(), t.sets.end());
        const SceneFile scene = load_scene_file(t.scene, sets);
        if (!scene.variety.variety_file.empty()) clumps.insert(scene.variety.variety_file);
        const std::string clump = scene_clump_file(scene.doc, t.scene);
        if (!clump.empty()) clumps.insert(clump);
      } catch (const std::exception&) {
        // an unreadable scene or override is reported when it runs
      }
    }
  }
  std::map<std::string, std::string> named;  // by their study-relative names, in that order
  for (const auto& clump : clumps) named[name_of(clump)] = clump;
  for (const auto& [name, clump] : named) all += "\n--- " + name + "\n" + read_text(clump);
  return fnv1a_hex(all);
}

}  // namespace

std::string study_fingerprint(const StudyConfig& s) {
  return fingerprint_with(s, [&](const std::string& path) { return study_relative_name(path, s.file); });
}

std::string study_fingerprint_as_spelt(const StudyConfig& s) {
  return fingerprint_with(s, [](const std::string& path) { return path; });
}

}  // namespace seedcal
