// The pick along the solution curve (curve_stage.cpp) on responses known in closed form, run by an
// executor that evaluates a formula instead of a DEM scene: on a curve (a line in the arc length)
// and over a flat target's box (a plane), the picked point is where the test's model meets its
// experiment; a test that does not answer keeps the confirmed point; its runs become the test's
// verification.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>

#include "calibrate/pipeline/pipeline.hpp"
#include "calibrate/pipeline/progress.hpp"
#include "tests/support/cli.hpp"

namespace seedcal {
namespace {

// Evaluates the verification test's metric "h" as a formula of the two parameters (a, b).
class FormulaExecutor final : public Executor {
 public:
  FormulaExecutor(const StudyConfig& s, std::function<double(double, double)> h) : study_(s), h_(std::move(h)) {}
  int slots() const override { return 1; }
  std::string describe() const override { return "formula"; }
  void run(const std::vector<EvalRequest>& requests, const RecordCallback& done, const DispatchCheck&) override {
    for (std::size_t i = 0; i < requests.size(); ++i) {
      EvaluationRecord r = request_record(study_, requests[i]);
      r.status = "ok";
      r.metrics["status"] = "ok";
      r.metrics[study_.scene_of(requests[i].target).metric] =
          h_(requests[i].inputs["a"].get<double>(), requests[i].inputs["b"].get<double>());
      done(i, r);
    }
  }

 private:
  const StudyConfig& study_;
  std::function<double(double, double)> h_;
};

class CurvePick : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::scratch_dir("curve-pick");
    const std::string scene = testing::source_dir() + "/data/scenes/examples/impact.toml";
    const std::string text = "name = \"curve\"\n[[target]]\nscene = \"" + scene + "\"\nmetric = \"y\"\nvalue = 1.0\n"
                             "[[parameter]]\npath = \"a\"\nlow = 0.0\nhigh = 1.0\ncalibrate = true\n"
                             "[[parameter]]\npath = \"b\"\nlow = 0.0\nhigh = 1.0\ncalibrate = true\n"
                             "[verify]\ncurve_points = 4\n[[verify.test]]\nname = \"check\"\nscene = \"" + scene +
                             "\"\nmetric = \"h\"\nvalue = 13.3\nsd = 0.5\n";
    std::filesystem::create_directories(dir_);
    testing::write_text(dir_ + "/study.toml", text);
    study_ = read_study(dir_ + "/study.toml");
    st_.kept = {0, 1};
    st_.nominal = Eigen::Vector2d(0.5, 0.5);
    st_.box_lo = Eigen::Vector2d(0.0, 0.0);
    st_.box_hi = Eigen::Vector2d(1.0, 1.0);
    st_.chosen = Eigen::Vector2d(0.5, 0.5);
    st_.posterior = {{"identified", {{"a", false}, {"b", false}}}};
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  nlohmann::json pick(const std::function<double(double, double)>& h) {
    StudyStore store = StudyStore::create(dir_ + "/study.h5", {"hash", study_.text, "test", "now"});
    FormulaExecutor executor(study_, h);
    Progress progress(dir_ + "/calibrate.log", false, 1);
    StudyEvaluator ev(study_, store, executor, progress);
    const nlohmann::json r = run_curve_pick(ev, st_, store, dir_);
    std::filesystem::remove(dir_ + "/study.h5");
    return r;
  }
  // keep_pick_in_posterior after a pick, with the posterior the target and the test gave together
  // (here set by hand: its 95 % intervals, median and mode, and whether the pick and the median lie
  // in its 95 % highest-density region).
  nlohmann::json keep_in(const nlohmann::json& interval, const nlohmann::json& median, bool pick_in_region,
                         bool median_in_region = true, nlohmann::json mode = nullptr) {
    if (mode.is_null()) mode = median;
    st_.posterior = {{"identified", {{"a", false}, {"b", false}}}, {"calibrated_interval", interval}, {"median", median},
                     {"mode", mode}, {"in_hpd95", {{"calibrated", pick_in_region}, {"median", median_in_region}}}};
    StudyStore store = StudyStore::create(dir_ + "/study.h5", {"hash", study_.text, "test", "now"});
    const nlohmann::json r = keep_pick_in_posterior(study_, st_, store);
    std::filesystem::remove(dir_ + "/study.h5");
    return r;
  }
  std::string dir_;
  StudyConfig study_;
  PipelineState st_;
};

// A noise-free plane fits exactly: the pick is exact to rounding.
constexpr double kExact = 1e-9;

TEST_F(CurvePick, AlongTheCurveTheLineMeetsTheExperiment) {
  // The curve: the box's diagonal, a = b = 0.5 + 0.5 u; h = 10 + 4 a + b = 10 + 5 s along it, so
  // h = 13.3 at s = 0.66, a = b = 0.66.
  st_.curve_path = doe::CurvePath({Eigen::Vector2d(-1.0, -1.0), Eigen::Vector2d(1.0, 1.0)});
  const auto r = pick([](double a, double b) { return 10.0 + 4.0 * a + b; });
  ASSERT_FALSE(r.contains("skipped")) << r.dump(1);
  EXPECT_EQ(r["mode"], "curve");
  EXPECT_TRUE(r["answers"].get<bool>());
  EXPECT_NEAR(r["s_picked"].get<double>(), 0.66, kExact);
  EXPECT_NEAR(st_.chosen(0), 0.66, kExact);
  EXPECT_NEAR(st_.chosen(1), 0.66, kExact);
  EXPECT_EQ(r["points"].size(), 4u);
  // The verification from these runs: the line at the point, i.e. the experiment.
  EXPECT_NEAR(st_.curve_verification["mean"].get<double>(), 13.3, kExact);
  EXPECT_EQ(st_.curve_verification["n"], 4);
  EXPECT_EQ(st_.curve_scene, 1);
}

TEST_F(CurvePick, OverAFlatTargetsBoxThePlanePicksTheNearestPoint) {
  // No curve: the plane over the box. In coded units h = 12.5 + 2 u1 + 0.5 u2; from the confirmed
  // point u0 = 0 the nearest point with h = 13.3 is 0.8 / 4.25 (2, 0.5).
  const auto r = pick([](double a, double b) { return 10.0 + 4.0 * a + b; });
  ASSERT_FALSE(r.contains("skipped")) << r.dump(1);
  EXPECT_EQ(r["mode"], "region");
  EXPECT_TRUE(r["answers"].get<bool>());
  EXPECT_NEAR(st_.chosen(0), 0.5 + 0.5 * 2.0 * 0.8 / 4.25, kExact);
  EXPECT_NEAR(st_.chosen(1), 0.5 + 0.5 * 0.5 * 0.8 / 4.25, kExact);
  EXPECT_NEAR(curve_prediction(st_, Eigen::Vector2d(2.0 * 0.8 / 4.25, 0.5 * 0.8 / 4.25)).mean, 13.3, kExact);
  // The corners, (1, 1) last.
  EXPECT_EQ(r["points"][3]["at"]["a"], 1.0);
  EXPECT_EQ(r["points"][3]["at"]["b"], 1.0);
  EXPECT_FALSE(r.contains("at_end"));
}

TEST_F(CurvePick, BeyondTheBoxThePointNearestInResponseIsPicked) {
  // h = 13.3 lies beyond the box's largest response, 10 + 2 a + b = 13 at (1, 1): that corner.
  const auto r = pick([](double a, double b) { return 10.0 + 2.0 * a + b; });
  EXPECT_TRUE(r.contains("at_end")) << r.dump(1);
  EXPECT_NEAR(st_.chosen(0), 1.0, kExact);
  EXPECT_NEAR(st_.chosen(1), 1.0, kExact);
}

TEST_F(CurvePick, APickOutsideThePosteriorsRegionMovesToItsMedian) {
  // The plane meets the experiment beyond the box, so the corner (1, 1) is picked; a posterior
  // whose 95 % highest-density region leaves it out moves the point to its median, and the test's
  // verification is the plane there (exact: the response is a plane).
  pick([](double a, double b) { return 10.0 + 2.0 * a + b; });
  ASSERT_NEAR(st_.chosen(0), 1.0, kExact);
  const auto r = keep_in({{"a", {0.02, 0.98}}, {"b", {0.1, 0.9}}}, {{"a", 0.5}, {"b", 0.45}}, false);
  ASSERT_FALSE(r.is_null());
  EXPECT_NE(r["reason"].get<std::string>().find("a 1 (95 % interval 0.02 .. 0.98), b 1 (95 % interval 0.1 .. 0.9), lies "
                                                "outside the 95 % highest-density region"),
            std::string::npos)
      << r.dump(1);
  EXPECT_NE(r["reason"].get<std::string>().find("the posterior's median"), std::string::npos) << r.dump(1);
  EXPECT_TRUE(st_.posterior["in_hpd95"]["calibrated"].get<bool>());
  EXPECT_EQ(st_.chosen(0), 0.5);
  EXPECT_EQ(st_.chosen(1), 0.45);
  EXPECT_EQ(st_.curve["picked"]["a"], 0.5);
  EXPECT_EQ(st_.curve["picked_by_plane"]["a"], 1.0);
  EXPECT_TRUE(st_.curve.contains("moved_into_posterior_region"));
  EXPECT_NEAR(st_.curve_verification["mean"].get<double>(), 10.0 + 2.0 * 0.5 + 0.45, kExact);
  EXPECT_NEAR(st_.curve_verification["rel_error"].get<double>(), 11.45 / 13.3 - 1.0, kExact);
  EXPECT_EQ(st_.curve["verification"], st_.curve_verification);
}

// The posterior's edge flags follow the calibrated point when the pick moves, without the
// posterior being taken again: a point at the parameters' limits is flagged, the median inside the
// intervals is not, and the store's posterior stage says the same.
TEST_F(CurvePick, EdgeFlagsFollowThePointWhenThePickMoves) {
  StudyStore store = StudyStore::create(dir_ + "/study.h5", {"hash", study_.text, "test", "now"});
  st_.posterior = {{"identified", {{"a", false}, {"b", false}}}, {"at_edge", nlohmann::json::object()}};
  st_.posterior_lo_coded = Eigen::Vector2d(-0.9, -0.8);
  st_.posterior_hi_coded = Eigen::Vector2d(0.9, 0.8);
  st_.chosen = Eigen::Vector2d(1.0, 1.0);
  refresh_edge_flags(study_, st_, store);
  EXPECT_NE(st_.posterior["at_edge"].value("a", std::string()).find("at its limit"), std::string::npos) << st_.posterior.dump(1);
  EXPECT_NE(st_.posterior["at_edge"].value("b", std::string()).find("at its limit"), std::string::npos);
  EXPECT_EQ(store.stages()["posterior"]["at_edge"], st_.posterior["at_edge"]);
  st_.chosen = Eigen::Vector2d(0.5, 0.45);
  refresh_edge_flags(study_, st_, store);
  EXPECT_TRUE(st_.posterior["at_edge"].empty()) << st_.posterior.dump(1);
  EXPECT_TRUE(store.stages()["posterior"]["at_edge"].empty());
  // An interval that runs into a limit flags the value that lies inside it.
  st_.posterior_hi_coded = Eigen::Vector2d(0.99, 0.8);
  refresh_edge_flags(study_, st_, store);
  EXPECT_NE(st_.posterior["at_edge"].value("a", std::string()).find("runs into its max"), std::string::npos) << st_.posterior.dump(1);
  std::filesystem::remove(dir_ + "/study.h5");
}

TEST_F(CurvePick, APickInsideThePosteriorsRegionStays) {
  st_.curve_path = doe::CurvePath({Eigen::Vector2d(-1.0, -1.0), Eigen::Vector2d(1.0, 1.0)});
  pick([](double a, double b) { return 10.0 + 4.0 * a + b; });
  const double mean = st_.curve_verification["mean"].get<double>();
  EXPECT_TRUE(keep_in({{"a", {0.6, 0.7}}, {"b", {0.6, 0.7}}}, {{"a", 0.65}, {"b", 0.65}}, true).is_null());
  EXPECT_NEAR(st_.chosen(0), 0.66, kExact);
  EXPECT_NEAR(st_.chosen(1), 0.66, kExact);
  EXPECT_FALSE(st_.curve.contains("moved_into_posterior_region"));
  EXPECT_EQ(st_.curve_verification["mean"].get<double>(), mean);
  // Outside a parameter's central interval but inside the region (a posterior flat in b, whose
  // central interval leaves out the ends of its range): the pick stays.
  EXPECT_TRUE(keep_in({{"a", {0.6, 0.7}}, {"b", {0.2, 0.6}}}, {{"a", 0.65}, {"b", 0.4}}, true).is_null());
  EXPECT_NEAR(st_.chosen(1), 0.66, kExact);
  // Outside the region: both parameters move to the median (the point stays on the posterior's
  // ridge, not half on the line's pick).
  EXPECT_FALSE(keep_in({{"a", {0.6, 0.7}}, {"b", {0.2, 0.6}}}, {{"a", 0.65}, {"b", 0.4}}, false).is_null());
  EXPECT_EQ(st_.chosen(0), 0.65);
  EXPECT_EQ(st_.chosen(1), 0.4);
  EXPECT_TRUE(st_.curve.contains("picked_by_line"));
}

TEST_F(CurvePick, AMedianOffTheRegionGivesWayToTheMode) {
  // A posterior bent along a curve: its marginal medians can fall between its arms, off the
  // region; the point of highest density is taken instead.
  pick([](double a, double b) { return 10.0 + 2.0 * a + b; });
  const auto r = keep_in({{"a", {0.1, 0.9}}, {"b", {0.1, 0.9}}}, {{"a", 0.5}, {"b", 0.5}}, false, false, {{"a", 0.2}, {"b", 0.8}});
  ASSERT_FALSE(r.is_null());
  EXPECT_NE(r["reason"].get<std::string>().find("the posterior's mode"), std::string::npos) << r.dump(1);
  EXPECT_EQ(st_.chosen(0), 0.2);
  EXPECT_EQ(st_.chosen(1), 0.8);
  EXPECT_NEAR(st_.curve_verification["mean"].get<double>(), 10.0 + 2.0 * 0.2 + 0.8, kExact);
}

TEST_F(CurvePick, AFlatTestKeepsTheConfirmedPoint) {
  // A response that alternates between the corners (an interaction only): the plane has no slope.
  const auto r = pick([](double a, double b) { return 13.0 + ((a > 0.5) == (b > 0.5) ? 0.4 : -0.4); });
  EXPECT_FALSE(r["answers"].get<bool>()) << r.dump(1);
  EXPECT_EQ(r["note"], "the test's model is flat: the confirmed point is kept");
  EXPECT_EQ(st_.chosen(0), 0.5);
  EXPECT_EQ(st_.chosen(1), 0.5);
}

TEST_F(CurvePick, AWeakSlopeMovesThePointAndSaysSo) {
  // A slope with a residual as large (one residual df): not significant, the point still moves to
  // where the plane meets the experiment, and the note says the evidence is weak.
  const auto r = pick([](double a, double b) { return 12.5 + 0.6 * (a - 0.5) + ((a > 0.5) == (b > 0.5) ? 0.4 : -0.4); });
  EXPECT_FALSE(r["answers"].get<bool>()) << r.dump(1);
  EXPECT_NE(r["note"].get<std::string>().find("not told from zero"), std::string::npos) << r.dump(1);
  EXPECT_GT(st_.chosen(0), 0.5);
}

TEST_F(CurvePick, IdentifiedOrSwitchedOffSkips) {
  st_.posterior = {{"identified", {{"a", true}, {"b", true}}}};
  EXPECT_EQ(pick([](double, double) { return 0.0; })["skipped"], "the target alone identifies both kept parameters");
}

}  // namespace
}  // namespace seedcal
