// End-to-end: `seedcal doe design|analyze|gp` run as a user would (binary from SEEDCAL_BINARY):
// exit codes, CSV columns, JSON keys, and the numbers of Montgomery's Example 11.2 in natural units.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

namespace {

struct Result {
  int code = -1;
  std::string out;
};

Result run(const std::string& args) {
  const char* b = std::getenv("SEEDCAL_BINARY");
  const std::string cmd = std::string(b ? b : "build/seedcal") + " " + args + " 2>&1";
  Result r;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf{};
  std::size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.out.append(buf.data(), n);
  const int s = pclose(p);
  r.code = WIFEXITED(s) ? WEXITSTATUS(s) : -1;
  return r;
}

std::string dir() {
  static const std::string d = [] {
    const auto p = std::filesystem::temp_directory_path() / ("seedcal-doe-cli-" + std::to_string(::getpid()));
    std::filesystem::create_directories(p);
    return p.string();
  }();
  return d;
}

std::string write(const std::string& name, const std::string& text) {
  const std::string path = dir() + "/" + name;
  std::ofstream(path) << text;
  return path;
}

std::string read(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

int lines(const std::string& s) {
  int n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

// Montgomery, DAE 8th ed., Example 11.2 (rotatable CCD, alpha = sqrt 2), natural units.
const char* kCcd =
    "time,temp,yield\n80,170,76.5\n80,180,77.0\n90,170,78.0\n90,180,79.5\n85,175,79.9\n85,175,80.3\n85,175,80.0\n"
    "85,175,79.7\n85,175,79.8\n92.0710678118654755,175,78.4\n77.9289321881345245,175,75.6\n"
    "85,182.0710678118654755,78.5\n85,167.9289321881345245,77.0\n";

TEST(DoeCli, DesignWritesNaturalAndCodedColumns) {
  const std::string out = dir() + "/ccd.csv";
  const auto r = run("doe design ccd --factor time=80:90 --factor temp=170:180 --center 5 --out " + out);
  ASSERT_EQ(r.code, 0) << r.out;
  const std::string csv = read(out);
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "run,std_order,time,temp,time_coded,temp_coded");
  EXPECT_EQ(lines(csv), 1 + 13);
  const auto pb = run("doe design pb --num-factors 7 --runs 12 --randomize --seed 4");
  ASSERT_EQ(pb.code, 0) << pb.out;
  EXPECT_NE(pb.out.find("dummy4"), std::string::npos);
  EXPECT_EQ(lines(pb.out), 1 + 12);
  for (const char* k : {"ff --num-factors 4 --generators D=ABC", "bbd --num-factors 3", "lhs --num-factors 2 --runs 7"})
    EXPECT_EQ(run(std::string("doe design ") + k).code, 0) << k;
}

TEST(DoeCli, AnalyzeJsonHasTheContractKeysAndTheBookNumbers) {
  const std::string data = write("ccd112.csv", kCcd);
  const auto r = run("doe analyze " + data + " --response yield --model quadratic --json");
  ASSERT_EQ(r.code, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* k : {"coefficients", "anova", "r2", "adj_r2", "pred_r2"}) EXPECT_TRUE(j.contains(k)) << k;
  for (const char* t : {"intercept", "time", "temp", "time:temp", "time^2", "temp^2"})
    EXPECT_TRUE(j["coefficients"].contains(t)) << t;
  // The book's equation in actual factors (printed to 5 decimals): half a unit of the last digit.
  EXPECT_NEAR(j["coefficients"]["intercept"].get<double>(), -1430.52285, 5e-6);
  EXPECT_NEAR(j["coefficients"]["time^2"].get<double>(), -0.05505, 5e-6);
  std::vector<std::string> sources;
  for (const auto& row : j["anova"]) {
    for (const char* k : {"source", "df", "ss", "ms", "f", "p"}) EXPECT_TRUE(row.contains(k)) << k;
    sources.push_back(row["source"]);
  }
  EXPECT_EQ(sources, (std::vector<std::string>{"model", "time", "temp", "time:temp", "time^2", "temp^2", "residual",
                                               "lack of fit", "pure error", "total"}));
  EXPECT_NEAR(j["anova"][0]["f"].get<double>(), 79.85, 0.005);  // printed 79.85
  EXPECT_TRUE(j["anova"].back()["f"].is_null());                 // no test on the total row
  EXPECT_FALSE(j.contains("effects"));                           // five levels: not a two-level design
  // Human-readable by default.
  const auto t = run("doe analyze " + data + " --response yield --model quadratic");
  ASSERT_EQ(t.code, 0);
  EXPECT_NE(t.out.find("lack of fit"), std::string::npos);
}

TEST(DoeCli, DesignThenAnalyzeGivesEffectsAgainstDummyColumns) {
  const std::string design = dir() + "/pb.csv";
  ASSERT_EQ(run("doe design pb --factor a=0:1 --factor b=10:20 --factor c=-1:1 --runs 8 --out " + design).code, 0);
  // Append a response y = 5 + 2 a - 0.3 b (+ a small pattern) to every row.
  std::istringstream in(read(design));
  std::string line, out;
  std::getline(in, line);
  out = line + ",y\n";
  int i = 0;
  while (std::getline(in, line)) {
    std::vector<double> v;
    std::stringstream s(line);
    for (std::string f; std::getline(s, f, ',');) v.push_back(std::stod(f));
    out += line + "," + std::to_string(5 + 2 * v[2] - 0.3 * v[3] + 0.01 * ((i++ * 7) % 5)) + "\n";
  }
  const std::string data = write("pb-y.csv", out);
  const auto r = run("doe analyze " + data + " --response y --model linear --json");
  ASSERT_EQ(r.code, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["factors"], (std::vector<std::string>{"a", "b", "c"}));
  ASSERT_TRUE(j.contains("effects"));
  EXPECT_EQ(j["effects_error"], "dummy columns");
  EXPECT_NEAR(j["effects"][1]["effect"].get<double>(), -3.0, 0.02);  // b over 10 units, plus the pattern
  EXPECT_EQ(j["effects"][1]["pareto_rank"], 1);
}

TEST(DoeCli, GaussianProcessPredictsAndProposes) {
  std::string csv = "x,z,y\n";
  for (int i = 0; i < 15; ++i) {
    const double x = (i % 5) * 0.25, z = (i / 5) * 0.5;
    csv += std::to_string(x) + "," + std::to_string(z) + "," + std::to_string(std::sin(3 * x) + z * z) + "\n";
  }
  const std::string data = write("gp.csv", csv);
  const std::string pts = write("pts.csv", "x,z\n0.5,0.5\n0.1,0.9\n");
  const std::string json_out = dir() + "/gp.json";
  const auto r = run("doe gp " + data + " --response y --predict " + pts + " --next 2 --json --out " + json_out);
  ASSERT_EQ(r.code, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* k : {"length_scales", "signal_variance", "noise_variance", "loo_rmse", "predictions", "next_points"})
    EXPECT_TRUE(j.contains(k)) << k;
  ASSERT_EQ(j["predictions"].size(), 2u);
  // (0.5, 0.5) is a data point of a noise-free function: the GP passes through it (1e-3 on a
  // response of range ~2: the fitted noise floor allows ~1e-5).
  EXPECT_NEAR(j["predictions"][0]["mean"].get<double>(), std::sin(1.5) + 0.25, 1e-3);
  EXPECT_EQ(j["next_points"].size(), 2u);
  EXPECT_EQ(nlohmann::json::parse(read(json_out)), j);
}

TEST(DoeCli, BadInputExitsTwoNamingFileColumnAndValue) {
  const std::string data = write("ccd-bad.csv", std::string(kCcd) + "85,175,abc\n");
  const auto r = run("doe analyze " + data + " --response yield");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("ccd-bad.csv:15: column yield = 'abc': not a finite number"), std::string::npos) << r.out;
  const auto c = run("doe analyze " + write("ccd.csv", kCcd) + " --response yld");
  EXPECT_EQ(c.code, 2);
  EXPECT_NE(c.out.find("--response = yld: no such column (columns: time, temp, yield)"), std::string::npos) << c.out;
  const auto f = run("doe design ccd --factor time=90:80");
  EXPECT_EQ(f.code, 2);
  EXPECT_NE(f.out.find("--factor time=90:80: must look like NAME=LOW:HIGH with LOW < HIGH"), std::string::npos) << f.out;
  const auto p = run("doe design pb --num-factors 5 --runs 10");
  EXPECT_EQ(p.code, 2);
  EXPECT_NE(p.out.find("PlackettBurmanOptions.runs = 10: must be one of 8, 12, 16, 20, 24"), std::string::npos) << p.out;
  // A quadratic model on a two-level design: the square is aliased with the intercept.
  const auto q = run("doe analyze " + write("ff.csv", "a,b,y\n-1,-1,1\n1,-1,2\n-1,1,3\n1,1,5\n-1,-1,1.1\n1,1,5.2\n") +
                     " --response y --model quadratic");
  EXPECT_EQ(q.code, 2);
  EXPECT_NE(q.out.find("term a^2: aliased"), std::string::npos) << q.out;
  EXPECT_EQ(run("doe analyze " + data + " --response yield --model cubic").code, 2);
}

}  // namespace
