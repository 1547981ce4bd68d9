// `seedcal export` end to end on a study directory made by hand: a summary.json as `seedcal
// calibrate` writes it for tests/cli/mini/export_study.toml (its recorded text and fingerprint,
// made-up calibrated values, model "manual-7" chosen), so no study has to run. The exported files
// carry the chosen model and the values; bad input exits 2 naming the file, key and value.
// tests/validation/export_settle/compare.py runs a real study and the exported deck in LIGGGHTS.
#include <filesystem>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "calibrate/pipeline/study_config.hpp"
#include "tests/support/cli.hpp"

namespace seedcal::testing {
namespace {

class ExportCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = scratch_dir("export");
    study_file_ = source_dir() + "/tests/cli/mini/export_study.toml";
    text_ = read_text(study_file_);
    summary_ = {{"schema_version", 2},
                {"study", "export-mini"},
                {"stage_reached", "done"},
                {"converged", true},
                {"calibrated", {{"seed_steel.restitution", 0.61}}},
                {"held_at_nominal", {{"seed_seed.static_friction", 0.55}}},
                {"model_selection", {{"chosen", "manual-7"}, {"comparison", "made up for the test"}}},
                {"provenance",
                 {{"study_file", study_file_},
                  {"config", text_},
                  {"config_hash", study_fingerprint(read_study_text(text_, study_file_))}}}};
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  CliResult run_export(const nlohmann::json& summary, const std::string& args) {
    write_text(dir_ + "/summary.json", summary.dump(1));
    return run_cli("export " + dir_ + " " + args);
  }

  std::string dir_, study_file_, text_;
  nlohmann::json summary_;
};

std::string csv_value(const std::string& csv, const std::string& key) {
  const std::size_t at = csv.find("\n" + key + ",");
  if (at == std::string::npos) return "";
  const std::size_t start = at + key.size() + 2;
  return csv.substr(start, csv.find(',', start) - start);
}

TEST_F(ExportCli, WritesTheChosenModelWithTheStudysValues) {
  auto r = run_export(summary_, "--format csv --out " + dir_ + "/csv");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string params = read_text(dir_ + "/csv/parameters.csv");
  EXPECT_EQ(csv_value(params, "clump.spheres"), "7");  // manual-7
  EXPECT_EQ(csv_value(params, "seed_steel.restitution"), "0.61");
  EXPECT_EQ(csv_value(params, "seed_seed.static_friction"), "0.55");
  EXPECT_EQ(csv_value(params, "contact.model"), "hertz_mindlin");  // the target's set
  const std::string spheres = read_text(dir_ + "/csv/spheres.csv");
  EXPECT_NE(spheres.find("\n7,"), std::string::npos);
  EXPECT_EQ(spheres.find("\n8,"), std::string::npos);
  EXPECT_NE(spheres.find("clump model \"manual-7\": chosen by the study's model selection"), std::string::npos);
  // The study's rig warnings travel with its values.
  nlohmann::json warned = summary_;
  warned["warnings"] = {"test shear, model manual-7: the box is 5.1 seed lengths across"};
  r = run_export(warned, "--format csv --out " + dir_ + "/warned");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::string header = read_text(dir_ + "/warned/parameters.csv");  // comment lines wrap: unwrap them
  for (std::size_t at = header.find("\n# "); at != std::string::npos; at = header.find("\n# ", at))
    header.replace(at, 3, " ");
  EXPECT_NE(header.find("the study's scenes warned (the values were fitted on this rig): test shear, model manual-7: "
                        "the box is 5.1 seed lengths across"),
            std::string::npos)
      << header;

  r = run_export(summary_, "--format liggghts --out " + dir_ + "/lig --count 120");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string fragment = read_text(dir_ + "/lig/in.seedcal_model");
  EXPECT_NE(fragment.find("nspheres 7 "), std::string::npos);
  EXPECT_NE(fragment.find("coefficientRestitution peratomtypepair 2 0.45 0.61 0.61 0.5\n"), std::string::npos);
  EXPECT_NE(read_text(dir_ + "/lig/in.settle").find("variable count index 120\n"), std::string::npos);

  // The values from another test's scene: the verification test (the same file and set here).
  r = run_export(summary_, "--format csv --out " + dir_ + "/check --test \"rebound check\"");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(read_text(dir_ + "/check/parameters.csv").find("test \"rebound check\""), std::string::npos);

  // A study without a model selection exports its first, calibrated model.
  nlohmann::json none = summary_;
  none.erase("model_selection");
  r = run_export(none, "--format csv --out " + dir_ + "/first");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(csv_value(read_text(dir_ + "/first/parameters.csv"), "clump.spheres"), "9");
}

TEST_F(ExportCli, BadInputExitsTwoNamingTheKey) {
  const auto expect_bad = [&](const nlohmann::json& summary, const std::string& args, const std::string& says) {
    const CliResult r = run_export(summary, args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(says), std::string::npos) << args << "\n" << r.output;
  };
  const std::string out = " --out " + dir_ + "/x";
  expect_bad(summary_, "--format vtk" + out, "--format");
  expect_bad(summary_, "--format csv", "--out");
  const CliResult missing = run_cli("export " + dir_ + "/nowhere --format csv" + out);
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.output.find("nowhere: no such directory"), std::string::npos) << missing.output;

  nlohmann::json s = summary_;
  s["stage_reached"] = "surrogate";
  expect_bad(s, "--format csv" + out, "summary.json: stage_reached = \"surrogate\": the study is not finished");
  s = summary_;
  s["provenance"]["config_hash"] = "0123456789abcdef";
  expect_bad(s, "--format csv" + out, "provenance.config_hash = \"0123456789abcdef\"");
  s = summary_;
  s["model_selection"]["chosen"] = "manual-5";
  expect_bad(s, "--format csv" + out, "model_selection.chosen = \"manual-5\": the study has no such [[model]]");
  s = summary_;
  s["calibrated"].erase("seed_steel.restitution");
  expect_bad(s, "--format csv" + out, "parameter \"seed_steel.restitution\" has no value");
  expect_bad(summary_, "--format csv --test nope" + out, "--test = \"nope\": the study has no such test (allowed: \"rebound\"");

  // The study file moved: named by --study, it is found again.
  s = summary_;
  s["provenance"]["study_file"] = "moved/export_study.toml";
  expect_bad(s, "--format csv" + out, "provenance.study_file = \"moved/export_study.toml\": no such file");
  EXPECT_EQ(run_export(s, "--format csv --study " + study_file_ + out).exit_code, 0);
  EXPECT_FALSE(std::filesystem::exists(dir_ + "/x/in.settle"));
}

}  // namespace
}  // namespace seedcal::testing
