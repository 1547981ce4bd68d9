// `seedcal report` end to end: a tiny real study (report_test_study.hpp) leaves report.html,
// report.md and the CSV tables behind; every section with data is there, every plot is an inline
// <svg> in the HTML and a file beside the Markdown, no "nan" anywhere; `seedcal report DIR`
// renders the same again; a directory without a study is bad input (exit 2).
#include <filesystem>
#include <regex>

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

}  // namespace
}  // namespace seedcal::testing
