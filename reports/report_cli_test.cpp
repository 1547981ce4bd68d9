// `seedcal report` end to end: a tiny real study (report_test_study.hpp) leaves report.html,
// report.md and the CSV tables behind; every section with data is there, every plot is an inline
// <svg> in the HTML and a file beside the Markdown, no "nan" anywhere; `seedcal report DIR`
// renders the same again; a directory without a study is bad input (exit 2).
#include <filesystem>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "reports/report_test_study.hpp"

namespace seedcal::testing {
namespace {

namespace fs = std::filesystem;

bool has_nan(const std::string& text) { return std::regex_search(text, std::regex("\\bnan\\b", std::regex::icase)); }

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
  return n;
}

// The fields of one CSV line (RFC 4180: a quoted field may hold commas and doubled quotes).
std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (std::size_t k = 0; k < line.size(); ++k) {
    const char c = line[k];
    if (quoted && c == '"' && k + 1 < line.size() && line[k + 1] == '"') {
      out.back() += '"';
      ++k;
    } else if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      out.emplace_back();
    } else if (c != '\r') {
      out.back() += c;
    }
  }
  return out;
}

TEST(ReportCli, StudyWritesTheReportAndReportRendersItAgain) {
  const std::string dir = scratch_dir("report-cli");
  const std::string out = run_report_study(dir);
  ASSERT_FALSE(out.empty());
  ASSERT_TRUE(fs::exists(out + "/report.html")) << "seedcal calibrate did not write the report";
  fs::remove(out + "/report.html");
  const auto r = run_cli("report " + out);
  ASSERT_EQ(r.exit_code, 0) << r.output;

  const std::string html = read_text(out + "/report.html"), md = read_text(out + "/report.md");
  for (const char* heading : {"Study inputs", "Screening design and responses", "Effects and their significance", "Steepest ascent",
                              "Response-surface design", "Surrogate fit: ANOVA and fit statistics",
                              "Fitted surface, target contour and solution", "Leave-one-out cross-validation",
                              "Optimiser and confirmation trace", "Final summary", "Verification", "Model selection"}) {
    EXPECT_NE(html.find(std::string("<h2>") + heading + "</h2>"), std::string::npos) << heading;
    EXPECT_NE(md.find(std::string("## ") + heading), std::string::npos) << heading;
  }
  // Each plot: an inline SVG in the HTML, a file the Markdown links.
  for (const char* plot : {"effects_pareto", "surface_contour", "gp_loo", "confirmation_trace", "model_selection_pareto"}) {
    EXPECT_NE(html.find(std::string("<figure id=\"plot-") + plot + "\">\n<svg"), std::string::npos) << plot;
    EXPECT_NE(md.find(std::string("(report/") + plot + ".svg)"), std::string::npos) << plot;
    EXPECT_NE(read_text(out + "/report/" + plot + ".svg").find("<svg"), std::string::npos) << plot;
  }
  EXPECT_EQ(count(html, "<svg"), count(html, "<figure id=\"plot-"));
  EXPECT_EQ(html.find("<script"), std::string::npos);
  EXPECT_EQ(html.find("Needs a newer study store"), std::string::npos);  // this store has everything
  // The contour plot shows the traced solution curve (two unknowns, one target) and the ANOVA rows.
  EXPECT_NE(read_text(out + "/report/surface_contour.svg").find("traced solution curve"), std::string::npos);
  for (const char* csv : {"study", "parameters", "targets", "screening_design", "effects", "surface_design", "fit_statistics", "anova",
                          "coefficients", "loo_predictions", "solver_rounds", "confirmation_rounds", "summary", "calibrated_values",
                          "confirmed", "verification", "model_selection", "verification_by_model"}) {
    const std::string path = out + "/report/" + csv + ".csv";
    ASSERT_TRUE(fs::exists(path)) << path;
    EXPECT_NE(md.find(std::string("(report/") + csv + ".csv)"), std::string::npos) << csv;
  }
  const std::string anova = read_text(out + "/report/anova.csv");
  EXPECT_EQ(anova.rfind("source,SS,df,MS,F,p,significance\n", 0), 0u) << anova;
  EXPECT_NE(anova.find("residual"), std::string::npos) << anova;
  EXPECT_NE(read_text(out + "/report/verification.csv").find("simulation only"), std::string::npos);
  for (const auto& e : fs::recursive_directory_iterator(out)) {
    const auto ext = e.path().extension();
    if (ext == ".html" || ext == ".md" || ext == ".csv") {
      EXPECT_FALSE(has_nan(read_text(e.path().string()))) << e.path();
    }
  }

  const auto missing = run_cli("report " + dir + "/no-such-study");
  EXPECT_EQ(missing.exit_code, 2) << missing.output;
  fs::remove_all(dir);
}

// A `seedcal study` directory (KIND.json files, no study store): `seedcal report DIR` renders the
// studies report, one section per study with its table as CSV and its plot as inline SVG; the
// paper's numbers stand beside seedcal's. The JSON here has the shape the study commands write.
TEST(ReportCli, StudyDirectoryGetsTheStudiesReport) {
  const std::string dir = scratch_dir("report-studies");
  write_text(dir + "/multicontact.json", R"({"study": "multicontact", "repeats": 3, "sets": [], "seed": 1,
    "free_drop": {"hertz_mindlin": {"rebound_height_m": {"mean": 0.035, "sd": 0.009, "n": 3, "samples": [0.03, 0.035, 0.04]},
                                    "contact_points": {"mean": 4.0, "sd": 1.0, "n": 3, "samples": [3, 4, 5]}},
                  "hmnr": {"rebound_height_m": {"mean": 0.055, "sd": 0.008, "n": 3, "samples": [0.05, 0.055, 0.06]},
                           "contact_points": {"mean": 4.0, "sd": 1.0, "n": 3, "samples": [3, 4, 5]}},
                  "rebound_relative_difference": 0.571,
                  "paper": {"hertz_mindlin_rebound_height_m": 0.0415, "hertz_mindlin_sd_m": 0.00836,
                            "hmnr_rebound_height_m": 0.058, "hmnr_sd_m": 0.00676, "note": "188 spheres"}}})");
  write_text(dir + "/stiffness.json", R"({"study": "stiffness", "repeats": 2, "paper": "Figure 26",
    "rows": [{"youngs_modulus_pa": 1.65e6, "status": "failed", "failure": {"message": "deep overlap: youngs_modulus_pa"},
              "contact_points": {"mean": null, "sd": null, "n": 0, "samples": []},
              "rebound_height_m": {"mean": null, "sd": null, "n": 0, "samples": []}},
             {"youngs_modulus_pa": 1.65e7, "status": "ok", "contact_points": {"mean": 7.0, "sd": 1.8, "n": 2, "samples": [6, 8]},
              "rebound_height_m": {"mean": 0.0525, "sd": 0.01, "n": 2, "samples": [0.045, 0.06]}},
             {"youngs_modulus_pa": 1.65e8, "status": "ok", "contact_points": {"mean": 4.1, "sd": 1.0, "n": 2, "samples": [3, 5]},
              "rebound_height_m": {"mean": 0.0551, "sd": 0.0085, "n": 2, "samples": [0.05, 0.06]}}],
    "contact_points_fall_with_E": true, "rebound_rises_with_E": true})");
  write_text(dir + "/tradeoff.json", R"({"study": "tradeoff", "scene": "bulk_density.toml", "sets": ["fidelity=quick"], "repeats": 3,
    "tolerance": 0.05, "metric": "bulk_density_kg_m3", "sweeps": [
      {"parameter": "rayleigh_fraction", "reference": 0.05, "cheapest_within_tolerance": 0.2, "rows": [
        {"value": 0.05, "index": {"mean": 688.7, "sd": 7.4, "n": 3}, "relative_change": 0.0, "significant": false,
         "cpu_seconds_per_run": 136.6, "steps_per_run": 491389, "speedup": 1.0, "within_tolerance": true, "status": "ok"},
        {"value": 0.2, "index": {"mean": 683.7, "sd": 9.4, "n": 3}, "relative_change": -0.0072, "significant": false,
         "cpu_seconds_per_run": 31.5, "steps_per_run": 115955, "speedup": 4.34, "within_tolerance": true, "status": "ok"},
        {"value": 0.4, "index": {"mean": null, "sd": null, "n": 0}, "relative_change": null, "significant": null,
         "cpu_seconds_per_run": null, "steps_per_run": null, "speedup": null, "within_tolerance": false, "status": "refused",
         "failure": {"message": "use rayleigh_fraction <= 0.2585"}}]},
      {"parameter": "materials.seed.youngs_modulus_pa", "reference": 1.65e8, "cheapest_within_tolerance": 1.65e6, "rows": [
        {"value": 1.65e8, "index": {"mean": 683.7, "sd": 9.4, "n": 3}, "relative_change": 0.0, "significant": false,
         "cpu_seconds_per_run": 31.5, "steps_per_run": 115955, "speedup": 1.0, "within_tolerance": true, "status": "ok",
         "same_runs_as": "rayleigh_fraction = 0.2"},
        {"value": 1.65e6, "index": {"mean": 704.3, "sd": 6.7, "n": 3}, "relative_change": 0.030, "significant": true,
         "cpu_seconds_per_run": 7.3, "steps_per_run": 15506, "speedup": 4.72, "within_tolerance": true, "status": "ok"}]}]})");
  const auto r = run_cli("report " + dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string html = read_text(dir + "/report.html"), md = read_text(dir + "/report.md");
  for (const char* heading : {"Multi-contact study: Hertz-Mindlin (HM) against HMNR",
                              "Stiffness study: contact points and rebound height against E", "Speed against accuracy"}) {
    EXPECT_NE(html.find(std::string("<h2>") + heading + "</h2>"), std::string::npos) << heading;
    EXPECT_NE(md.find(std::string("## ") + heading), std::string::npos) << heading;
  }
  for (const char* plot : {"multicontact_drops", "stiffness", "tradeoff"})
    EXPECT_NE(read_text(dir + "/report/" + std::string(plot) + ".svg").find("<svg"), std::string::npos) << plot;
  EXPECT_EQ(count(html, "<svg"), 3u);
  for (const char* csv : {"multicontact", "stiffness", "tradeoff_rayleigh_fraction", "tradeoff_materials_seed_youngs_modulus_pa"})
    EXPECT_TRUE(fs::exists(dir + "/report/" + std::string(csv) + ".csv")) << csv;
  // The HMNR rebound row carries the study's mean and the paper's (58.0 mm, sd 6.76), in mm.
  bool hmnr_row = false;
  std::istringstream rows(read_text(dir + "/report/multicontact.csv"));
  for (std::string line; std::getline(rows, line);) {
    const std::vector<std::string> f = csv_fields(line);
    if (f.size() != 8 || f[1] != "HMNR" || f[2] != "rebound height, mm") continue;
    hmnr_row = true;
    EXPECT_DOUBLE_EQ(std::stod(f[3]), 55.0) << line;
    EXPECT_DOUBLE_EQ(std::stod(f[6]), 58.0) << line;
    EXPECT_DOUBLE_EQ(std::stod(f[7]), 6.76) << line;
  }
  EXPECT_TRUE(hmnr_row);
  EXPECT_NE(read_text(dir + "/report/tradeoff_rayleigh_fraction.csv").find("refused: use rayleigh_fraction"), std::string::npos);
  EXPECT_FALSE(has_nan(html));
  EXPECT_FALSE(has_nan(md));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace seedcal::testing
