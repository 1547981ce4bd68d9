// Verification of the calibrated model against the tests it was not fitted to (piling, bulk
// density, drum...: simulated mean and sd against the experiment), and the choice among clump
// models: accuracy (mean |relative error|) against CPU seconds, with the Pareto front.
#include <algorithm>
#include <cmath>

#include "reports/sections/common.hpp"
#include "reports/sections/sections.hpp"

namespace seedcal::reports {
namespace {

// One verification table row of a test result.
std::vector<std::string> test_row(const nlohmann::json& x) {
  const bool sim_only = !x.contains("experimental_mean") || x["experimental_mean"].is_null();
  return {x.value("test", std::string("?")), x.value("label", x.value("test", std::string("?"))), x.value("metric", std::string("")),
          format_value(x.value("mean", nlohmann::json())), format_value(x.value("sd", nlohmann::json())),
          format_value(x.value("n", nlohmann::json())),
          sim_only ? "simulation only" : format_value(x["experimental_mean"]),
          sim_only ? "simulation only" : format_value(x.value("experimental_sd", nlohmann::json())),
          sim_only ? "simulation only" : format_percent(x.value("rel_error", nlohmann::json())),
          sim_only ? "simulation only"
          : !x.value("within_sd", nlohmann::json()).is_null() ? format_value(x["within_sd"])
          : x.value("mean", nlohmann::json()).is_null()       ? "n/a (no result)"
                                                              : "n/a (no experimental sd)",
          format_value(x.value("cpu_seconds", nlohmann::json()))};
}

// What a note under a table is about: the test, and its model in the tables of every model.
std::string note_subject(const nlohmann::json& x, const std::string& model) {
  return x.value("test", std::string("?")) + (model.empty() ? "" : " (" + model + ")") + ":";
}

// The note for a test some of whose runs failed or were skipped, or "": how many, and the first
// reason (a test with no result says why).
std::string runs_note(const nlohmann::json& x, const std::string& model) {
  const auto& failed = member(x, "failures");
  const auto& skipped = member(x, "skipped");
  if (failed.empty() && skipped.empty()) return "";
  std::string n = note_subject(x, model);
  if (!failed.empty())
    n += " " + std::to_string(failed.size()) + " run(s) failed (the first: " + failed[0].value("status", std::string("?")) +
         ": " + failed[0].value("message", std::string()) + ")";
  if (!skipped.empty())
    n += std::string(failed.empty() ? "" : ";") + " " + std::to_string(skipped.size()) + " run(s) skipped (" +
         skipped[0].value("reason", std::string()) + ")";
  return n + ".";
}

// The note for a drum test whose bed slipped on the shell in some frames, or "".
std::string slipping_note(const nlohmann::json& x, const std::string& model) {
  const int slipping = x.value("drum_slipping_frames", 0);
  if (slipping <= 0) return "";
  return note_subject(x, model) + " the drum's shell slid under a bed at rest in " +
         std::to_string(slipping) + " of " + std::to_string(x.value("drum_frames", 0)) +
         " frames (wall layer below 0.1 of the shell's speed): those angles are held by the wall friction, not a dynamic angle of "
         "repose; a rougher drum wall (higher seed-wall friction) lets the shell carry the bed (docs/scenes/drum.md).";
}

const std::vector<std::string> kTestColumns = {"test", "label", "metric", "mean", "sd", "n", "experimental mean", "experimental sd",
                                               "relative error", "within experimental sd", "CPU seconds"};

void add_verification(const nlohmann::json& v, Document& doc) {
  Section s{"verification", "Verification", {}};
  if (v.contains("model")) s.paragraph("Model verified: " + format_value(v["model"]) + ".");
  Table t{"verification", "Verification tests: simulation against experiment", kTestColumns, {}, {}};
  for (const auto& x : member(v, "tests")) {  // with notes on failed, skipped and slipping runs
    t.add_row(test_row(x));
    if (auto n = runs_note(x, ""); !n.empty()) t.notes.push_back(std::move(n));
    if (auto n = slipping_note(x, ""); !n.empty()) t.notes.push_back(std::move(n));
  }
  t.notes.push_back("Relative error = simulated mean / experimental mean - 1; \"simulation only\": the study gives no experimental value.");
  s.table(std::move(t));
  doc.sections.push_back(std::move(s));
}

void add_selection(const nlohmann::json& m, const std::vector<ModelCalibration>& per, Document& doc) {
  Section s{"model-selection", "Model selection", {}};
  s.paragraph("Chosen: " + format_value(m.value("chosen", nlohmann::json())) + ". Rule: " + format_value(m.value("rule", nlohmann::json())) + ".");
  if (m.contains("note")) s.note(format_value(m["note"]));
  const std::string chosen = m.value("chosen", std::string());
  const auto& models = member(m, "models");
  bool any_score = false, any_calibrated = false;
  for (const auto& x : models) {
    any_score = any_score || x.contains("score");
    any_calibrated = any_calibrated || !member(x, "calibrated").empty();
  }
  Table t{"model_selection", "Clump models: accuracy against cost",
          {"model", "settings", "spheres", "mean |relative error|", "within experimental sd", "CPU seconds",
           any_score ? "score" : "accuracy per CPU second", "Pareto optimal", "chosen"}, {}, {}};
  if (any_calibrated) t.columns.push_back("calibrated values");
  Table by_model{"verification_by_model", "Verification tests of every model", {"model"}, {}, {}};
  by_model.columns.insert(by_model.columns.end(), kTestColumns.begin(), kTestColumns.end());
  struct Point { double cpu, err; bool pareto; std::string model; };
  std::vector<Point> pts;
  for (const auto& x : models) {
    const std::string model = x.value("model", std::string("?"));
    std::vector<std::string> row{model, format_value(x.value("set", nlohmann::json(""))), format_value(x.value("spheres", nlohmann::json())),
                                 format_percent(x.value("mean_abs_rel_error", nlohmann::json())),
                                 x.contains("tests_with_sd") ? format_value(x.value("within_sd", nlohmann::json())) + " of " +
                                                                   format_value(x["tests_with_sd"])
                                                             : "n/a",
                                 format_value(x.value("cpu_seconds", nlohmann::json())),
                                 format_value(x.value(any_score ? "score" : "accuracy_per_cpu_second", nlohmann::json())),
                                 format_value(x.value("pareto", nlohmann::json())), model == chosen ? "yes" : "no"};
    if (any_calibrated) {
      std::string cal;
      for (const auto& [k, v] : member(x, "calibrated").items()) cal += std::string(cal.empty() ? "" : ", ") + k + " = " + format_value(v);
      row.push_back(cal);
    }
    t.add_row(std::move(row));
    for (const auto& test : member(x, "tests")) {
      auto r = test_row(test);
      r.insert(r.begin(), model);
      by_model.add_row(std::move(r));
      if (auto n = runs_note(test, model); !n.empty()) by_model.notes.push_back(std::move(n));
      if (auto n = slipping_note(test, model); !n.empty()) by_model.notes.push_back(std::move(n));
    }
    pts.push_back({as_number(x.value("cpu_seconds", nlohmann::json())), 100.0 * std::fabs(as_number(x.value("mean_abs_rel_error", nlohmann::json()))),
                   x.value("pareto", false), model});
  }
  if (m.contains("comparison")) t.notes.push_back("Choice: " + format_value(m["comparison"]) + ".");
  if (m.contains("tied") && m["tied"].is_array()) {
    std::string ties;
    for (const auto& x : m["tied"]) ties += (ties.empty() ? "" : ", ") + format_value(x);
    t.notes.push_back("Errors that cannot be told apart from the lowest within the margin and the scatter: " + ties + ".");
  }
  if (m.contains("replicates_to_separate")) {
    if (m["replicates_to_separate"].is_object()) {
      std::string reps;
      for (const auto& [test, n] : m["replicates_to_separate"].items()) reps += (reps.empty() ? "" : ", ") + test + " " + format_value(n);
      t.notes.push_back("Replicates per test it would take to tell the chosen model from the most accurate one: " + reps + ".");
    } else if (m.contains("replicates_note")) {
      t.notes.push_back(format_value(m["replicates_note"]) + ".");
    }
  }
  if (m.contains("scatter_note")) t.notes.push_back("Tests " + format_value(m["scatter_note"]) + ".");
  if (m.contains("verified_at_note")) t.notes.push_back(format_value(m["verified_at_note"]) + ".");
  s.table(std::move(t));
  if (!by_model.rows.empty()) s.table(std::move(by_model));
  // [verify] calibrate_each_model: each model's own calibration.
  if (!per.empty()) {
    Table c{"calibration_per_model", "Each model calibrated under its own overrides ([verify] calibrate_each_model)",
            {"model", "parameter", "calibrated", "95 % interval", "identified", "converged", "DEM runs"}, {}, {}};
    for (const ModelCalibration& e : per) {
      for (const auto& [path, v] : e.calibrated) {
        std::string iv = "n/a", identified = "n/a";
        if (e.calibrated_interval && e.calibrated_interval->count(path))
          iv = format_value(e.calibrated_interval->at(path)[0]) + " .. " + format_value(e.calibrated_interval->at(path)[1]);
        if (e.identified && e.identified->count(path)) identified = format_value(e.identified->at(path));
        c.add_row({e.model, path, format_value(v), iv, identified, format_value(e.converged), format_value(e.evaluations)});
      }
    }
    s.table(std::move(c));
  }
  std::string all, front, pick;
  std::vector<Point> sorted = pts;
  std::sort(sorted.begin(), sorted.end(), [](const Point& a, const Point& b) { return a.cpu < b.cpu; });
  for (const auto& p : sorted) {
    if (!std::isfinite(p.cpu) || !std::isfinite(p.err)) continue;
    const std::string line = gp_number(p.cpu) + " " + gp_number(p.err) + " " + gp_data_string(p.model) + "\n";
    all += line;
    if (p.pareto) front += line;
    if (p.model == chosen) pick += line;
  }
  if (!all.empty()) {
    GnuplotPlot p;
    p.data = {{"all.dat", all}, {"front.dat", front}, {"chosen.dat", pick}};
    p.script = "set title 'Clump models: mean |relative error| against CPU seconds'\nset xlabel 'CPU seconds (calibration and verification runs)'\n"
               "set ylabel 'mean |relative error| (%)'\nset grid\nset offsets graph 0.08, graph 0.12, graph 0.12, graph 0.08\n"
               "set key outside right top vertical\n"
               "plot 'front.dat' using 1:2 with lines lw 2 lc rgb '#1f77b4' title 'Pareto front', "
               "'all.dat' using 1:2 with points pt 7 ps 1.3 lc rgb '#555555' title 'models', "
               "'all.dat' using 1:2:3 with labels offset 0,1.2 notitle, "
               "'chosen.dat' using 1:2 with points pt 6 ps 3 lw 2.5 lc rgb '#ff7f0e' title 'chosen'\n";
    add_plot(s, "model_selection_pareto", "Model selection: accuracy against cost, the Pareto front and the chosen model", p);
  }
  doc.sections.push_back(std::move(s));
}

}  // namespace

void add_verification_sections(const StudyData& d, Document& doc) {
  if (!d.summary) return;
  if (d.summary->verification.is_object()) add_verification(d.summary->verification, doc);
  if (d.summary->model_selection.is_object()) add_selection(d.summary->model_selection, d.summary->calibration_per_model, doc);
}

}  // namespace seedcal::reports
