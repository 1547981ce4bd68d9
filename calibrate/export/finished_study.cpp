#include "calibrate/export/finished_study.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "calibrate/pipeline/evaluation.hpp"
#include "calibrate/pipeline/study_config.hpp"
#include "store/errors.hpp"

namespace seedcal {
namespace {

namespace fs = std::filesystem;

nlohmann::json read_summary(const std::string& path) {
  std::ifstream in(path);
  if (!in)
    throw InputError(path + ": cannot open the file: a study directory holds the summary.json that `seedcal calibrate "
                            "STUDY.toml --out DIR` writes");
  try {
    return nlohmann::json::parse(in);
  } catch (const std::exception& e) {
    throw InputError(path + ": not JSON (" + std::string(e.what()) + ")");
  }
}

// summary.json's `key` (dotted), which must be of `type` ("string", "object").
const nlohmann::json& summary_member(const nlohmann::json& j, const std::string& path, const std::string& key,
                             const std::string& type) {
  const nlohmann::json* v = &j;
  std::string walked;
  std::istringstream parts(key);
  for (std::string part; std::getline(parts, part, '.');) {
    walked += (walked.empty() ? "" : ".") + part;
    if (!v->is_object() || !v->contains(part))
      throw InputError(path + ": " + walked + " is missing (a summary.json of `seedcal calibrate` has it)");
    v = &(*v)[part];
  }
  const bool ok = type == "string" ? v->is_string() : type == "object" ? v->is_object() : true;
  if (!ok) throw InputError(path + ": " + key + " = " + v->dump() + ": must be a JSON " + type);
  return *v;
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
  const nlohmann::json summary = read_summary(summary_path);
  const std::string stage = summary_member(summary, summary_path, "stage_reached", "string").get<std::string>();
  if (stage != "done")
    throw InputError(summary_path + ": stage_reached = \"" + stage +
                     "\": the study is not finished (allowed: \"done\"); finish it with `seedcal calibrate STUDY.toml "
                     "--out " + o.study_dir + " --resume`");
  const std::string recorded_file = summary_member(summary, summary_path, "provenance.study_file", "string").get<std::string>();
  const std::string text = summary_member(summary, summary_path, "provenance.config", "string").get<std::string>();
  const std::string hash = summary_member(summary, summary_path, "provenance.config_hash", "string").get<std::string>();
  const nlohmann::json& calibrated = summary_member(summary, summary_path, "calibrated", "object");
  const nlohmann::json& held = summary_member(summary, summary_path, "held_at_nominal", "object");

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
  if (summary.contains("model_selection") && summary["model_selection"].is_object()) {
    const nlohmann::json& sel = summary["model_selection"];
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
    const nlohmann::json* v = calibrated.contains(p.path) ? &calibrated[p.path]
                              : held.contains(p.path)     ? &held[p.path]
                                                          : nullptr;
    if (!v || !v->is_number())
      throw InputError(summary_path + ": calibrated / held_at_nominal: parameter \"" + p.path +
                       "\" has no value (a finished study gives every parameter one)");
    point[p.path] = v->get<double>();
  }
  const StudyTarget& t = s.scene_of(test);
  const StudyModel& chosen = s.models.at(model);
  ExportedModel m = exported_model_from_scene(t.scene, scene_overrides(chosen, t, point));
  m.study_name = summary.value("study", s.name);
  m.study_dir = o.study_dir;
  m.model_name = chosen.name;
  m.model_reason = reason;
  m.test_name = t.name;
  m.converged = summary.value("converged", false);
  m.calibrated = calibrated;
  m.held_at_nominal = held;
  return m;
}

}  // namespace seedcal
