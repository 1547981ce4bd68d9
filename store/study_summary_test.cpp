// The typed summary (store/study_summary.hpp): what to_json writes, summary_from_json reads back
// unchanged; an older summary reads with defaults; a member of the wrong type is named.
#include "store/study_summary.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "store/errors.hpp"
#include "store/study_store.hpp"

namespace seedcal {
namespace {

StudySummary full_summary() {
  StudySummary s;
  s.schema_version = kStudyStoreSchemaVersion;
  s.study = "round-trip";
  s.stage_reached = "done";
  s.calibrated = {{"seed_seed.static_friction", 0.61}, {"seed_seed.rolling_friction", 0.05}};
  s.held_at_nominal = {{"seed_seed.restitution", 0.45}};
  s.targets = {{"shear_strength_pa", 118230.0}};
  ConfirmedTarget c;
  c.target = 118230.0;
  c.samples = {117000.0, 121000.0, 119500.0};
  c.seeds = {7, 8, 18446744073709551557ULL};  // the largest 64-bit prime: seeds are unsigned 64-bit
  ConfirmedStats& x = c.stats.emplace();
  x.mean = 119166.7;
  x.sd = 2020.7;
  x.cv = 0.017;
  x.rel_error = 0.0079;
  x.rel_error_ci = {-0.034, 0.050};
  x.confidence = 0.95;
  x.within_tolerance = true;
  x.significant_miss = false;
  x.replicates_to_resolve_tolerance = 12;
  s.confirmed["shear_strength_pa"] = c;
  s.converged = true;
  s.confirmation_rounds = 2;
  s.evaluations = 41;
  s.evaluations_total = 59;
  s.evaluations_from_store = 3;
  s.classical_workflow_evaluations = 93;
  s.tolerance = 0.05;
  s.calibrated_interval = {{"seed_seed.static_friction", {0.4, 0.8}}};
  s.identified = {{"seed_seed.static_friction", false}, {"seed_seed.rolling_friction", true}};
  ModelCalibration m;
  m.model = "auto-11";
  m.stage_prefix = "model:auto-11/";
  m.calibrated_yet = true;
  m.calibrated = {{"seed_seed.static_friction", 0.7}};
  m.converged = false;
  m.evaluations = 30;
  m.identified = std::map<std::string, bool>{{"seed_seed.static_friction", true}};
  m.curve_picked = {{"seed_seed.static_friction", 0.7}};
  s.calibration_per_model = {ModelCalibration{"manual-9", "", false, {}, false, {}, -1, {}, {}, {}}, m};
  s.cpu_seconds = 600.5;
  s.calibration_cpu_seconds = 400.0;
  s.verification_cpu_seconds = 200.5;
  s.wall_seconds = 320.0;
  s.provenance = {"0.9.0+abc", "data/studies/x.toml", "fnv:1234", "name = \"x\"\n", 42};
  s.warnings = {"test shear, model manual-9: the box is 5.1 seed lengths across"};
  s.solution_set = {{"found", true}};
  s.posterior = {{"mode", {{"seed_seed.static_friction", 0.6}}}};
  s.curve = {{"test", "piling"}};
  s.verification = {{"tests", nlohmann::json::array()}};
  s.model_selection = {{"chosen", "manual-9"}};
  s.stages = {{"screen", {{"kept", {"seed_seed.static_friction"}}}}};
  return s;
}

TEST(StudySummary, WhatIsWrittenReadsBackUnchanged) {
  const nlohmann::json j = to_json(full_summary());
  const StudySummary back = summary_from_json(j, "summary.json");
  EXPECT_EQ(to_json(back), j);
  EXPECT_EQ(back.confirmed.at("shear_strength_pa").seeds.back(), 18446744073709551557ULL);
  ASSERT_TRUE(back.confirmed.at("shear_strength_pa").stats.has_value());
  EXPECT_EQ(back.confirmed.at("shear_strength_pa").stats->replicates_to_resolve_tolerance, 12);
  EXPECT_EQ(j["confirmed"]["shear_strength_pa"]["n"], 3);
  // A model whose calibration has not reported carries its name and prefix only.
  EXPECT_FALSE(j["calibration_per_model"][0].contains("calibrated"));
  EXPECT_TRUE(j["calibration_per_model"][1].contains("curve_picked"));
}

TEST(StudySummary, UnreportedStagesAndUnsetMembersAreLeftOut) {
  StudySummary s;
  s.schema_version = kStudyStoreSchemaVersion;
  s.stage_reached = "screen";
  ConfirmedTarget c;
  c.target = 1.0;
  c.samples = {1.1};
  c.note = "fewer than two replicates finished: nothing is confirmed";
  s.confirmed["m"] = c;
  const nlohmann::json j = to_json(s);
  for (const char* key : {"posterior", "curve", "verification", "model_selection", "calibration_per_model"})
    EXPECT_FALSE(j.contains(key)) << key;
  EXPECT_TRUE(j["solution_set"].is_object());
  EXPECT_FALSE(j["confirmed"]["m"].contains("mean"));
  // JSON has no NaN: an unset tolerance is written as null and reads back as NaN.
  EXPECT_NE(j.dump().find("\"tolerance\":null"), std::string::npos);
  EXPECT_TRUE(std::isnan(summary_from_json(nlohmann::json::parse(j.dump()), "summary.json").tolerance));
  EXPECT_EQ(to_json(summary_from_json(nlohmann::json::parse(j.dump()), "summary.json")).dump(), j.dump());
}

TEST(StudySummary, AnOlderSummaryReadsWithDefaults) {
  // The first summaries had no schema_version, no posterior and no per-model calibration.
  const auto j = nlohmann::json::parse(R"({"study": "old", "stage_reached": "done", "converged": true,
    "calibrated": {"a": 1.5}, "held_at_nominal": {}, "evaluations": 20})");
  const StudySummary s = summary_from_json(j, "old/summary.json");
  EXPECT_EQ(s.schema_version, 1);
  EXPECT_EQ(s.calibrated.at("a"), 1.5);
  EXPECT_TRUE(s.identified.empty());
  EXPECT_TRUE(s.posterior.is_null());
  EXPECT_TRUE(s.warnings.empty());
}

TEST(StudySummary, AMemberOfTheWrongTypeIsNamedWithItsFile) {
  const auto bad = [](const char* text) {
    try {
      summary_from_json(nlohmann::json::parse(text), "dir/summary.json");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(bad(R"({"calibrated": {"a": "x"}})").find("dir/summary.json: calibrated.a is not a number"), std::string::npos);
  EXPECT_NE(bad(R"({"confirmed": {"m": {"mean": 1, "rel_error_ci": [0]}}})").find("confirmed.m.rel_error_ci is not an array of two numbers"),
            std::string::npos);
  EXPECT_NE(bad(R"({"provenance": {"seed": -1}})").find("provenance.seed is not a non-negative integer"), std::string::npos);
  EXPECT_NE(bad("[1, 2]").find("the document is not an object"), std::string::npos);
  EXPECT_NE(bad(R"({"warnings": ["a", 2]})").find("warnings[1] is not a string"), std::string::npos);
  // Written by a newer build: refused, both versions named.
  const std::string newer = bad(("{\"schema_version\": " + std::to_string(kStudyStoreSchemaVersion + 1) + "}").c_str());
  EXPECT_NE(newer.find("schema_version = " + std::to_string(kStudyStoreSchemaVersion + 1)), std::string::npos) << newer;
}

}  // namespace
}  // namespace seedcal
