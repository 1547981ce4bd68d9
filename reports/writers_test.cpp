// Unit tests of the report writers: HTML and Markdown escaping, CSV quoting, number formatting
// (never "nan"), SVG inlining, gnuplot rendering, and a report built from a hand-made study
// directory (summary.json with verification and model selection, an older store's stages without
// the newer keys, scene pictures and a shear curve).
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>
#include <sstream>
#include <unistd.h>

#include <gtest/gtest.h>

#include "reports/gnuplot_svg.hpp"
#include "reports/html_writer.hpp"
#include "reports/markdown_writer.hpp"
#include "reports/report.hpp"
#include "store/errors.hpp"

namespace seedcal::reports {
namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

bool has_nan(const std::string& text) { return std::regex_search(text, std::regex("\\bnan\\b", std::regex::icase)); }

bool gnuplot_available() {
  return std::system("gnuplot --version > /dev/null 2>&1") == 0;
}

TEST(Escaping, HtmlEscapesMarkupAndQuotes) {
  EXPECT_EQ(escape_html("<a href=\"x\">&'</a>"), "&lt;a href=&quot;x&quot;&gt;&amp;&#39;&lt;/a&gt;");
  EXPECT_EQ(escape_html("plain text 1.5e-3"), "plain text 1.5e-3");
}

TEST(Escaping, MarkdownEscapesTableAndEmphasisCharacters) {
  EXPECT_EQ(escape_markdown("seed_seed.static_friction"), "seed\\_seed.static\\_friction");
  EXPECT_EQ(escape_markdown("a|b *c* [d] <e> `f` #g\\"), "a\\|b \\*c\\* \\[d\\] \\<e\\> \\`f\\` \\#g\\\\");
  EXPECT_EQ(escape_markdown("two\nlines"), "two lines");
}

TEST(Csv, QuotesOnlyWhatNeedsIt) {
  EXPECT_EQ(csv_field("plain"), "plain");
  EXPECT_EQ(csv_field("a,b"), "\"a,b\"");
  EXPECT_EQ(csv_field("say \"hi\""), "\"say \"\"hi\"\"\"");
  EXPECT_EQ(csv_field("two\nlines"), "\"two\nlines\"");
  Table t{"t", "caption", {"name", "value"}, {}, {}};
  t.add_row({"x,y", "1.5"});
  t.add_row({"z", "n/a"});
  EXPECT_EQ(to_csv(t), "name,value\n\"x,y\",1.5\nz,n/a\n");
  EXPECT_THROW(t.add_row({"only one"}), std::logic_error);
}

TEST(Numbers, NonFiniteIsNotAvailable) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(format_number(nan), "n/a");
  EXPECT_EQ(format_number(inf), "n/a");
  EXPECT_EQ(format_number(-inf), "n/a");
  EXPECT_EQ(format_number(-0.0), "0");
  EXPECT_EQ(format_number(118230.00000014946), "118230");
  EXPECT_EQ(format_number(0.05040370459764347), "0.0504037");
  EXPECT_EQ(format_value(nlohmann::json(nullptr)), "n/a");
  EXPECT_EQ(format_value(nlohmann::json(true)), "yes");
  EXPECT_EQ(format_value(nlohmann::json(93)), "93");
  EXPECT_EQ(format_value(nlohmann::json::array({1.5, nullptr})), "1.5, n/a");
  EXPECT_EQ(format_percent(nlohmann::json(-0.035)), "-3.50 %");
  EXPECT_EQ(format_percent(nlohmann::json(nullptr)), "n/a");
  EXPECT_EQ(file_stem("drum 5 rpm/x"), "drum_5_rpm_x");
}

TEST(Svg, InlinedIdsArePrefixedAndPrologDropped) {
  const std::string svg = "<?xml version=\"1.0\"?>\n<svg width=\"10\">\n<title>Gnuplot</title>\n<defs><path id='gpPt0'/></defs>"
                          "<use xlink:href='#gpPt0'/><g id=\"canvas\" clip-path=\"url(#clip1)\"/></svg>\n";
  const std::string s = inline_svg(svg, "p3-", "a <b>");
  EXPECT_EQ(s.rfind("<svg", 0), 0u) << s;
  EXPECT_NE(s.find("id='p3-gpPt0'"), std::string::npos) << s;
  EXPECT_NE(s.find("href='#p3-gpPt0'"), std::string::npos) << s;
  EXPECT_NE(s.find("id=\"p3-canvas\""), std::string::npos) << s;
  EXPECT_NE(s.find("url(#p3-clip1)"), std::string::npos) << s;
  EXPECT_NE(s.find("<title>a &lt;b&gt;</title>"), std::string::npos) << s;
}

TEST(Writers, HtmlAndMarkdownShowTheSameTable) {
  Document doc;
  doc.title = "T <1>";
  Section s{"sec", "Section & more", {}};
  Table t{"tab", "A table", {"factor", "value"}, {}, {"a note"}};
  t.add_row({"seed_seed.static_friction", "0.5"});
  s.table(t);
  s.note("missing <data>");
  s.preformatted("file", "x = 1\n```\n");
  doc.sections.push_back(s);
  const std::string html = render_html(doc), md = render_markdown(doc);
  EXPECT_NE(html.find("<title>T &lt;1&gt;</title>"), std::string::npos);
  EXPECT_NE(html.find("<h2>Section &amp; more</h2>"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"num\">0.5</td>"), std::string::npos) << html;
  EXPECT_NE(html.find("href=\"report/tab.csv\""), std::string::npos);
  EXPECT_NE(html.find("missing &lt;data&gt;"), std::string::npos);
  EXPECT_EQ(html.find("<script"), std::string::npos);
  EXPECT_NE(md.find("| seed\\_seed.static\\_friction | 0.5 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| --- | --- |"), std::string::npos);
  EXPECT_NE(md.find("(report/tab.csv)"), std::string::npos);
  EXPECT_NE(md.find("````\nx = 1\n```\n````"), std::string::npos) << md;  // fence longer than the text's
}

TEST(Gnuplot, DrawsAnSvgWithoutScripts) {
  if (!gnuplot_available()) GTEST_SKIP() << "gnuplot is not installed";
  GnuplotPlot p;
  p.add_data("d.dat", {{1, 2}, {2, std::numeric_limits<double>::quiet_NaN()}, {3, 1}});
  EXPECT_EQ(p.data[0].second, "1 2\n3 1\n");  // the NaN row left out
  p.script = "set title " + gp_quote("it's a_b") + "\nplot 'd.dat' using 1:2 with lines title 'x'\n";
  const std::string svg = render_gnuplot_svg(p);
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  EXPECT_EQ(svg.find("<script"), std::string::npos);
  EXPECT_NE(svg.find("it's a_b"), std::string::npos);
  GnuplotPlot bad;
  bad.script = "plot 'no-such-file.dat'\n";
  EXPECT_THROW(render_gnuplot_svg(bad), std::runtime_error);
}

// A study directory without a store: summary.json with verification and model selection (the
// schema of the verification stage), a scene picture and a shear curve.
StudyData fixture(const fs::path& dir) {
  fs::create_directories(dir / "scenes" / "piling");
  fs::create_directories(dir / "scenes" / "shear");
  std::ofstream(dir / "scenes" / "piling" / "side_view.svg")
      << "<?xml version=\"1.0\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"100\" height=\"50\"><circle id=\"c\" cx=\"10\" cy=\"10\" r=\"5\"/></svg>\n";
  std::ofstream(dir / "scenes" / "shear" / "direct_shear_curve.csv")
      << "displacement_m,shear_stress_pa,smoothed_shear_stress_pa,normal_stress_pa,lid_height_m\n"
         "0,0,0,10000,0.02\n0.001,50000,45000,10000,0.02\n0.002,80000,78000,10000,0.02\n0.003,nan,79000,10000,0.02\n";
  StudyData d;
  d.dir = dir.string();
  d.summary = summary_from_json(nlohmann::json::parse(R"({
    "study": "fixture", "stage_reached": "done", "converged": true, "evaluations": 40, "classical_workflow_evaluations": 93,
    "cpu_seconds": 600.5, "wall_seconds": 320.0, "tolerance": 0.02,
    "warnings": ["test shear, model manual-9: direct_shear.quick.diameter_m is small for the seed"],
    "calibrated": {"seed_seed.static_friction": 0.5}, "held_at_nominal": {"seed_seed.restitution": 0.45},
    "calibrated_interval": {"seed_seed.static_friction": [0.31, 0.88]}, "identified": {"seed_seed.static_friction": false},
    "posterior": {"reasons": {"seed_seed.static_friction": "95 % interval 0.31 .. 0.88"}, "in_hpd95": {"calibrated": true, "median": true}},
    "confirmed": {"shear_strength_pa": {"mean": 118000.0, "sd": 900.0, "n": 3, "rel_error": -0.002, "rel_error_ci": [-0.01, 0.006],
                  "target": 118230.0, "within_tolerance": true, "resolved": true}},
    "verification": {"model": "manual-9", "tests": [
      {"test": "piling", "metric": "angle_of_repose_deg", "label": "piling", "mean": 30.1, "sd": 1.2, "n": 3, "samples": [29, 30, 31.3],
       "experimental_mean": 31.2, "experimental_sd": 0.9, "rel_error": -0.035, "within_sd": false, "cpu_seconds": 40.0},
      {"test": "drum", "label": "drum 5 rpm", "rpm": 5, "metric": "dynamic_angle_deg", "mean": 35.0, "sd": 0.8, "n": 2,
       "experimental_mean": null, "experimental_sd": null, "rel_error": null, "within_sd": null, "cpu_seconds": 80.0,
       "drum_frames": 6, "drum_slipping_frames": 4},
      {"test": "shear", "label": "shear", "metric": "shear_strength_pa", "mean": 120000.0, "sd": 9000.0, "n": 2,
       "experimental_mean": 118230.0, "experimental_sd": null, "rel_error": 0.015, "within_sd": null, "cpu_seconds": 5.0},
      {"test": "heap-b", "label": "heap-b", "metric": "angle_of_repose_deg", "mean": null, "sd": null, "n": 0,
       "experimental_mean": 31.76, "experimental_sd": 1.16, "rel_error": null, "within_sd": null, "cpu_seconds": 3.0,
       "failures": [{"seed": 9, "status": "deep_overlap", "message": "overlap reached 0.5 of the radius"}],
       "skipped": [{"seed": 10, "reason": "model cannot be chosen"}, {"seed": 11, "reason": "model cannot be chosen"}]}]},
    "model_selection": {"rule": "cheapest model within 2 % of the lowest mean |error|", "chosen": "manual-9", "models": [
      {"model": "manual-9", "spheres": 9, "mean_abs_rel_error": 0.05, "cpu_seconds": 300.0, "score": 1.0, "pareto": true, "calibrated": {"seed_seed.static_friction": 0.5}},
      {"model": "auto-3", "spheres": 3, "mean_abs_rel_error": 0.12, "cpu_seconds": 90.0, "score": 0.7, "pareto": true, "calibrated": {"seed_seed.static_friction": 0.6}},
      {"model": "auto-20", "spheres": 20, "mean_abs_rel_error": 0.06, "cpu_seconds": 800.0, "score": 0.4, "pareto": false, "calibrated": {}}]}
  })"), "fixture summary.json");
  // An older store's solve stage: no ANOVA rows, no leave-one-out predictions, no prediction grid.
  d.has_store = true;
  d.stages["solve_round_1"] = nlohmann::json::parse(R"({
    "factors": ["seed_seed.static_friction"], "label": "solve_round_1",
    "solution": {"chosen": {"seed_seed.static_friction": 0.5}, "found": true, "predicted": {"shear": 118230.0}, "surrogate": "gp"},
    "targets": [{"name": "shear", "points": 7, "chosen": "gp", "choice_rule": "smaller leave-one-out RMSE",
                 "gp": {"loo_rmse": 1000.0, "noise_sd": 10.0, "signal_sd": 5000.0},
                 "quadratic": {"r2": 0.9, "adj_r2": 0.85, "pred_r2": null, "loo_rmse": 2000.0, "sigma": 300.0,
                               "coefficients_coded": {"intercept": 1.0}}}]})");
  return d;
}

TEST(Report, RendersVerificationModelSelectionAndScenesFromAFixture) {
  const fs::path dir = fs::temp_directory_path() / (std::string("seedcal-report-fixture-") + std::to_string(::getpid()));
  fs::remove_all(dir);
  const StudyData d = fixture(dir);
  const Document doc = build_report(d);
  std::vector<std::string> ids;
  for (const auto& s : doc.sections) ids.push_back(s.id);
  for (const char* id : {"summary", "verification", "model-selection", "scenes", "surrogate-fit", "surface-plot", "cross-validation"})
    EXPECT_NE(std::find(ids.begin(), ids.end(), id), ids.end()) << id;
  const auto files = write_report(doc, dir.string());
  EXPECT_FALSE(files.empty());
  const std::string html = slurp(dir / "report.html"), md = slurp(dir / "report.md");
  EXPECT_NE(html.find("simulation only"), std::string::npos);
  // An experiment with a mean and no sd: the error is given, the within-sd test is not applicable.
  EXPECT_NE(html.find("n/a (no experimental sd)"), std::string::npos);
  EXPECT_NE(html.find("drum 5 rpm"), std::string::npos);
  // A drum whose bed slipped on the shell says so under the table, in both formats; once.
  const std::string slip = "shell slid under a bed at rest in 4 of 6 frames";
  EXPECT_NE(html.find(slip), std::string::npos);
  EXPECT_NE(md.find(slip), std::string::npos);
  EXPECT_EQ(md.find(slip, md.find(slip) + 1), std::string::npos);
  // A test without a result says so, and why: its failed and skipped runs.
  EXPECT_NE(md.find("n/a (no result)"), std::string::npos) << md;
  EXPECT_NE(html.find("heap-b: 1 run(s) failed (the first: deep_overlap: overlap reached 0.5 of the radius); 2 run(s) "
                      "skipped (model cannot be chosen)."),
            std::string::npos);
  EXPECT_NE(html.find("Needs a newer study store"), std::string::npos);
  EXPECT_NE(md.find("The calibrated point lies inside the posterior's joint 95 % highest-density region."), std::string::npos) << md;
  // The rigs' warnings stand on the first screen, in both formats.
  const std::string warned = "test shear, model manual-9: direct_shear.quick.diameter_m is small for the seed";
  EXPECT_LT(html.find(warned), html.find("<h2>Study inputs</h2>"));
  EXPECT_NE(md.find("test shear, model manual-9: direct\\_shear.quick.diameter\\_m is small for the seed"), std::string::npos) << md;
  EXPECT_NE(md.find("(scenes/piling/side_view.svg)"), std::string::npos) << md;
  for (const char* f : {"verification.csv", "model_selection.csv", "summary.csv", "calibrated_values.csv", "confirmed.csv", "fit_statistics.csv"})
    EXPECT_TRUE(fs::exists(dir / "report" / f)) << f;
  if (gnuplot_available()) {
    for (const char* f : {"model_selection_pareto.svg", "shear_curve_shear.svg"}) EXPECT_TRUE(fs::exists(dir / "report" / f)) << f;
    EXPECT_NE(html.find("id=\"plot-model_selection_pareto\">\n<svg"), std::string::npos);
    EXPECT_NE(html.find("id=\"plot-scene_piling_side_view\">\n<svg"), std::string::npos);
  }
  for (const auto& f : files) EXPECT_FALSE(has_nan(slurp(f))) << f;
  // A second rendering removes what the first wrote and this one does not.
  std::ofstream(dir / "report" / "stale.csv") << "x\n";
  write_report(doc, dir.string());
  EXPECT_FALSE(fs::exists(dir / "report" / "stale.csv"));
  fs::remove_all(dir);
}

// One kept factor: the surface is drawn as a curve against it, with the runs, the target and the
// chosen value; the leave-one-out plot and table come from the fit's data.
TEST(Report, OneFactorSurfaceIsAProfile) {
  if (!gnuplot_available()) GTEST_SKIP() << "gnuplot is not installed";
  const fs::path dir = fs::temp_directory_path() / ("seedcal-report-profile-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  StudyData d;
  d.dir = dir.string();
  d.has_store = true;
  d.stages["solve_round_1"] = nlohmann::json::parse(R"({
    "factors": ["e"], "label": "solve_round_1",
    "solution": {"chosen": {"e": 2.0}, "found": true, "predicted": {"t": 4.0}, "surrogate": "quadratic"},
    "targets": [{"name": "t", "points": 3, "chosen": "quadratic", "choice_rule": "smaller leave-one-out RMSE",
                 "data": {"coded": [[-1], [0], [1]], "natural": [[1], [2], [3]], "observed": [1.0, 4.1, 8.9]},
                 "gp": {"loo_rmse": 1.0, "loo_predicted": [2.0, 4.5, 7.0]},
                 "quadratic": {"loo_rmse": 0.5, "loo_predicted": [1.2, null, 8.0]}}],
    "surface_grid": {"factors": ["e"], "x": [1, 2, 3], "held": {},
                     "targets": [{"name": "t", "target": 4.0, "surrogate": "quadratic", "z": [1.0, 4.0, 9.0]}]}})");
  const Document doc = build_report(d);
  const auto files = write_report(doc, dir.string());
  for (const char* f : {"surface_profile.svg", "gp_loo.svg", "loo_predictions.csv"}) EXPECT_TRUE(fs::exists(dir / "report" / f)) << f;
  const std::string loo = slurp(dir / "report" / "loo_predictions.csv");
  EXPECT_NE(loo.find("2,2,4.1,4.5,n/a"), std::string::npos) << loo;  // run, e, observed, GP, quadratic
  for (const auto& f : files) EXPECT_FALSE(has_nan(slurp(f))) << f;
  fs::remove_all(dir);
}

// A curve pick that the posterior put outside its interval: the curve section names the line's own
// point and why the calibrated point is the posterior's median.
TEST(Report, CurveSectionSaysWhenThePickMovedIntoThePosteriorsRegion) {
  StudyData d;
  d.summary.emplace();
  d.summary->curve = nlohmann::json::parse(R"({
    "mode": "curve", "test": "piling", "choice_rule": "named by the study", "model": "m", "metric": "angle_of_repose_deg",
    "experimental_mean": 31.76, "experimental_sd": 1.16, "s_picked": 0.0,
    "points": [{"s": 0.0, "at": {"mu_s": 0.9}, "value": 38.0, "seed": 1, "status": "ok"},
               {"s": 1.0, "at": {"mu_s": 0.3}, "value": 37.0, "seed": 2, "status": "ok"}],
    "response_model": {"terms": "y = intercept + s * s_arc", "coefficients": {"intercept": 38.0, "s": -1.0},
                       "standard_errors": {"intercept": 1.0, "s": 1.5}, "residual_sd": 1.0, "df": 0, "r2": 1.0, "p_slope": 0.7},
    "at_end": "the line meets the experiment beyond the curve's start (s = -6.24): the end is picked",
    "picked_by_line": {"mu_s": 0.9}, "picked": {"mu_s": 0.61},
    "moved_into_posterior_region": "the line's point, mu_s 0.9 (95 % interval 0.3 .. 0.85), lies outside the 95 % highest-density region that the target and the test give together"})");
  const Document doc = build_report(d);
  const auto it = std::find_if(doc.sections.begin(), doc.sections.end(), [](const Section& s) { return s.id == "curve"; });
  ASSERT_NE(it, doc.sections.end());
  std::string text;
  for (const auto& b : it->blocks)
    if (const auto* p = std::get_if<Paragraph>(&b)) text += p->text + "\n";
  EXPECT_NE(text.find("The line picked s = 0: mu_s = 0.9."), std::string::npos) << text;
  EXPECT_NE(text.find("But the line's point, mu_s 0.9 (95 % interval 0.3 .. 0.85), lies outside the 95 % highest-density region"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find(": mu_s = 0.61."), std::string::npos) << text;
}

TEST(Report, RepeatedIdsAreMadeUnique) {
  Document doc;
  Section s{"s", "S", {}};
  s.table(Table{"t", "a", {"x"}, {}, {}});
  s.table(Table{"t", "b", {"x"}, {}, {}});
  doc.sections.push_back(s);
  make_ids_unique(doc);
  EXPECT_EQ(std::get<Table>(doc.sections[0].blocks[0]).id, "t");
  EXPECT_EQ(std::get<Table>(doc.sections[0].blocks[1]).id, "t_2");
}

TEST(Report, DirectoryWithoutAStudyIsBadInput) {
  EXPECT_THROW(load_study("/nonexistent-seedcal-study"), InputError);
}

}  // namespace
}  // namespace seedcal::reports
