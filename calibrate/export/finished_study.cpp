#include "calibrate/export/finished_study.hpp"

#include <cmath>
#include <filesystem>

#include "calibrate/pipeline/evaluation.hpp"
#include "calibrate/pipeline/study_config.hpp"
#include "store/errors.hpp"
#include "store/study_summary.hpp"

namespace seedcal {
namespace {

namespace fs = std::filesystem;

// summary.json's `key`, which a finished study has: refused when the summary lacks it.
const std::string& required(const std::string& value, const std::string& path, const std::string& key) {
  if (value.empty()) throw InputError(path + ": " + key + " is missing (a summary.json of `seedcal calibrate` has it)");
  return value;
}

std::string describe_tests(const StudyConfig& s) {
  std::string names;
  for (int i = 0; i < s.scene_count(); ++i) names += (i ? ", \"" : "\"") + s.scene_of(i).name + "\"";
  return names;
}

}  // namespace

ExportedModel read_finished_study(const FinishedStudyOptions& o) {
  if (!fs::is_directory(o.study_dir))
    throw InputError(o.study_dir + ": no such directory (allowed: a study directory, `seedcal calibrate --out DIR`)");
  const std::string summary_path = (fs::path(o.study_dir) / "summary.json").string();
  const StudySummary summary = read_study_summary(summary_path);
  const std::string& stage = required(summary.stage_reached, summary_path, "stage_reached");
  if (stage != "done")
    throw InputError(summary_path + ": stage_reached = \"" + stage +
                     "\": the study is not finished (allowed: \"done\"); finish it with `seedcal calibrate STUDY.toml "
                     "--out " + o.study_dir + " --resume`");
  const std::string& recorded_file = required(summary.provenance.study_file, summary_path, "provenance.study_file");
  const std::string& text = required(summary.provenance.config, summary_path, "provenance.config");
  const std::string& hash = required(summary.provenance.config_hash, summary_path, "provenance.config_hash");
  const ParameterValues& calibrated = summary.calibrated;
  const ParameterValues& held = summary.held_at_nominal;

  const std::string study_file = o.study_file.empty() ? recorded_file : o.study_file;
  if (!fs::exists(study_file))
    throw InputError(o.study_file.empty()
                         ? summary_path + ": provenance.study_file = \"" + recorded_file +
                               "\": no such file from here (the path is as `seedcal calibrate` was given it); name "
                               "the study file with --study FILE"
                         : "--study = \"" + o.study_file + "\": no such file");
  // The study as it ran (its recorded text, after any --set), its paths resolved beside the study
  // file; the fingerprint covers that text and every scene and clump file it names.
  const StudyConfig s = read_study_text(text, study_file);
  const std::string now = study_fingerprint(s);
  if (now != hash)
    throw InputError(summary_path + ": provenance.config_hash = \"" + hash + "\", but the study's files read now give \"" +
                     now + "\": a scene or clump file that " + study_file +
                     " names changed since the study ran, so the export would not describe the calibrated seed "
                     "(allowed: the files the study ran with)");

  // The chosen clump model (stage 7), or the calibrated one when the study chose none.
  std::size_t model = 0;
  std::string reason = "the study's first model, the one it calibrated (it verified no other)";
  if (summary.model_selection.is_object()) {
    const nlohmann::json& sel = summary.model_selection;
    if (sel.contains("chosen") && sel["chosen"].is_string()) {
      const std::string name = sel["chosen"].get<std::string>();
      bool found = false;
      for (std::size_t k = 0; k < s.models.size() && !found; ++k)
        if (s.models[k].name == name) {
          model = k;
          found = true;
        }
      if (!found)
        throw InputError(summary_path + ": model_selection.chosen = \"" + name + "\": the study has no such [[model]]");
      reason = "chosen by the study's model selection (stage 7)";
      if (sel.contains("comparison") && sel["comparison"].is_string())
        reason += ": " + sel["comparison"].get<std::string>();
    } else {
      reason = "the study's first model, the one it calibrated: its model selection chose none (" +
               sel.value("note", std::string("no model has an error on every test")) + ")";
    }
  }

  int test = 0;
  if (!o.test.empty()) {
    test = -1;
    for (int i = 0; i < s.scene_count() && test < 0; ++i)
      if (s.scene_of(i).name == o.test) test = i;
    if (test < 0)
      throw InputError("--test = \"" + o.test + "\": the study has no such test (allowed: " + describe_tests(s) + ")");
  }
  // The values every run of the study's last stages used: each parameter calibrated or held.
  nlohmann::json point = nlohmann::json::object();
  for (const StudyParameter& p : s.parameters) {
    const auto c = calibrated.find(p.path), h = held.find(p.path);
    const double v = c != calibrated.end() ? c->second : h != held.end() ? h->second : std::nan("");
    if (!std::isfinite(v))
      throw InputError(summary_path + ": calibrated / held_at_nominal: parameter \"" + p.path +
                       "\" has no value (a finished study gives every parameter one)");
    point[p.path] = v;
  }
  const StudyTarget& t = s.scene_of(test);
  const StudyModel& chosen = s.models.at(model);
  ExportedModel m = exported_model_from_scene(t.scene, scene_overrides(chosen, t, point));
  m.study_name = summary.study.empty() ? s.name : summary.study;
  m.study_dir = o.study_dir;
  m.model_name = chosen.name;
  m.model_reason = reason;
  m.test_name = t.name;
  m.converged = summary.converged;
  m.warnings = summary.warnings;
  m.calibrated = calibrated;
  m.held_at_nominal = held;
  return m;
}

}  // namespace seedcal
