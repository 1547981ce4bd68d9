// The report in a browser: headless Chromium loads report.html of a tiny real study
// (report_test_study.hpp) from a file:// URL, dumps the DOM it built and takes a screenshot. The
// DOM must hold every section heading and every inline <svg> of the file (nothing failed to
// parse, nothing was fetched). The screenshot is kept in the build tree as an artifact:
// <build>/test-artifacts/report_screenshot.png. Skipped when Chromium is not installed.
#include <array>
#include <cstdlib>
#include <iostream>
#include <filesystem>
#include <regex>

#include <gtest/gtest.h>

#include "reports/report_test_study.hpp"

namespace seedcal::testing {
namespace {

namespace fs = std::filesystem;

// $SEEDCAL_CHROMIUM, or chromium / chromium-browser on PATH; "" when there is none.
std::string chromium() {
  if (const char* e = std::getenv("SEEDCAL_CHROMIUM"); e && *e) return e;
  for (const char* name : {"chromium", "chromium-browser", "google-chrome"})
    if (std::system((std::string("command -v ") + name + " > /dev/null 2>&1").c_str()) == 0) return name;
  return "";
}

std::vector<std::string> matches(const std::string& text, const std::regex& re) {
  std::vector<std::string> out;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), re); it != std::sregex_iterator(); ++it) out.push_back((*it)[1].str());
  return out;
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
  return n;
}

TEST(ReportBrowser, ChromiumLoadsEverySectionAndPlot) {
  const std::string browser = chromium();
  if (browser.empty()) GTEST_SKIP() << "chromium is not installed (Debian: apt-get install --no-install-recommends chromium)";
  const std::string dir = scratch_dir("report-browser");
  const std::string out = run_report_study(dir);
  ASSERT_FALSE(out.empty());
  const std::string html_path = fs::absolute(out + "/report.html").string();
  const std::string html = read_text(html_path);
  const auto headings = matches(html, std::regex("<h2>([^<]*)</h2>"));
  ASSERT_GE(headings.size(), 10u);
  const std::size_t svgs = count(html, "<svg");
  ASSERT_GE(svgs, 5u);

  // The artifact directory: beside the seedcal binary (the build tree).
  const fs::path artifacts = fs::absolute(fs::path(seedcal_binary()).parent_path() / "test-artifacts");
  fs::create_directories(artifacts);
  const std::string shot = (artifacts / "report_screenshot.png").string();
  fs::remove(shot);
  const std::string flags = " --headless --disable-gpu --no-sandbox --hide-scrollbars --user-data-dir=" + dir + "/profile ";
  const std::string url = "file://" + html_path;
  const auto dom = run_shell(browser + flags + "--dump-dom " + url + " 2>/dev/null");
  ASSERT_EQ(dom.exit_code, 0) << dom.output.substr(0, 2000);
  for (const auto& h : headings) EXPECT_NE(dom.output.find("<h2>" + h + "</h2>"), std::string::npos) << h;
  EXPECT_EQ(count(dom.output, "<svg"), svgs);
  const auto png = run_shell(browser + flags + "--window-size=1280,6000 --screenshot=" + shot + " " + url + " 2>&1");
  EXPECT_EQ(png.exit_code, 0) << png.output;
  EXPECT_TRUE(fs::exists(shot) && fs::file_size(shot) > 10000) << shot;
  std::cout << "screenshot: " << shot << "\n";
  fs::remove_all(dir);
}

}  // namespace
}  // namespace seedcal::testing
