// Trajectories of a calibration's runs: --trajectory's values, the requests that carry the
// setting to a worker (JSON), the plan that gives a confirmation's first replicate its folder and
// marks the verification's scene folders, and an evaluation that writes trajectory.h5 and
// trajectory.xdmf there with the same result as without (the miniature study: a two-sphere
// impact).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "calibrate/pipeline/progress.hpp"
#include "calibrate/pipeline/study_evaluator.hpp"
#include "tests/support/cli.hpp"

namespace seedcal {
namespace {

TEST(StudyTrajectories, StagesFromTheFlagsValue) {
  for (const auto& [value, verify, confirm] :
       {std::tuple{"", true, false}, {"verify", true, false}, {"confirm", false, true}, {"all", true, true}}) {
    StudyTrajectories t;
    std::string why;
    ASSERT_TRUE(parse_study_trajectories(value, &t, &why)) << value;
    EXPECT_EQ(t.verify, verify) << value;
    EXPECT_EQ(t.confirm, confirm) << value;
    EXPECT_TRUE(t.any());
    EXPECT_TRUE(t.IsValid(&why));
  }
  StudyTrajectories t;
  std::string why;
  EXPECT_FALSE(t.any());
  EXPECT_FALSE(parse_study_trajectories("screen", &t, &why));
  EXPECT_EQ(why, "--trajectory = \"screen\": must be verify, confirm or all");
  t.interval_s = -1.0;
  EXPECT_FALSE(t.IsValid(&why));
  EXPECT_EQ(why, "trajectory interval_s = -1: must be in (0, 1000]");
  EXPECT_EQ(path_slug("seed/steel 2"), "seed_steel_2");
  EXPECT_EQ(path_slug(""), "test");
}

TEST(StudyTrajectories, RequestsCarryTheIntervalToWorkers) {
  EvalRequest r;
  r.stage = "verify";
  r.inputs = nlohmann::json::object();
  r.out_dir = "out/scenes/a/b";
  r.trajectory_interval_s = 0.005;
  EXPECT_EQ(EvalRequest::from_json(r.to_json()).trajectory_interval_s, 0.005);
  r.trajectory_interval_s = 0.0;
  EXPECT_FALSE(r.to_json().contains("trajectory_interval_s"));  // older workers read the same JSON
  EXPECT_EQ(EvalRequest::from_json(r.to_json()).trajectory_interval_s, 0.0);
}

// Never asked to run: the planning below needs an executor to exist, not to work.
class NoExecutor final : public Executor {
 public:
  int slots() const override { return 1; }
  std::string describe() const override { return "none"; }
  void run(const std::vector<EvalRequest>&, const RecordCallback&, const DispatchCheck&) override {
    ADD_FAILURE() << "no run expected";
  }
};

class StudyTrajectoriesPlan : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::scratch_dir("study-trajectories");
    study_ = read_study(testing::source_dir() + "/tests/cli/mini/mpi_study.toml");
    nominal_ = Eigen::VectorXd(2);
    nominal_ << study_.parameters[0].nominal, study_.parameters[1].nominal;
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string dir_;
  StudyConfig study_;
  Eigen::VectorXd nominal_;
};

TEST_F(StudyTrajectoriesPlan, ConfirmationRoundsAndVerificationFoldersRecord) {
  StudyStore store = StudyStore::create(dir_ + "/study.h5", {"hash", study_.text, "test", "now"});
  NoExecutor executor;
  Progress progress(dir_ + "/calibrate.log", false, 1);
  StudyEvaluator ev(study_, store, executor, progress);
  // Not asked: no request records.
  for (const EvalRequest& r : ev.plan("confirm", nominal_, 2)) {
    EXPECT_TRUE(r.out_dir.empty());
    EXPECT_EQ(r.trajectory_interval_s, 0.0);
  }
  EXPECT_EQ(ev.plan_one("verify", nominal_, 0, 0, dir_ + "/scenes/m/t").trajectory_interval_s, 0.0);

  StudyTrajectories t;
  t.confirm = true;
  t.interval_s = 0.002;
  ev.record_trajectories(t, dir_);
  // The first replicate of each target (one target here) records, in the round's folder; the
  // study's second confirmation is round 02 (round 01 was planned above).
  const auto round = ev.plan("confirm", nominal_, 2);
  ASSERT_EQ(round.size(), 2u);
  EXPECT_EQ(round[0].out_dir, dir_ + "/trajectories/confirm/round_02/contact");
  EXPECT_EQ(round[0].trajectory_interval_s, 0.002);
  EXPECT_TRUE(round[1].out_dir.empty());
  EXPECT_EQ(round[1].trajectory_interval_s, 0.0);
  for (const EvalRequest& r : ev.plan("screen", nominal_, 1)) EXPECT_TRUE(r.out_dir.empty());
  // Verification was not asked for: its scene folder gets the CSV and picture only.
  EXPECT_EQ(ev.plan_one("verify", nominal_, 0, 0, dir_ + "/scenes/m/t").trajectory_interval_s, 0.0);
  t.verify = true;
  ev.record_trajectories(t, dir_);
  EXPECT_EQ(ev.plan_one("verify", nominal_, 0, 0, dir_ + "/scenes/m/t").trajectory_interval_s, 0.002);
  EXPECT_EQ(ev.plan_one("verify", nominal_, 0, 0).trajectory_interval_s, 0.0);  // a later replicate
  t.interval_s = 0.0;
  EXPECT_THROW(ev.record_trajectories(t, dir_), std::invalid_argument);
}

TEST_F(StudyTrajectoriesPlan, AnEvaluationWritesItsTrajectoryAndTheSameResult) {
  EvalRequest r;
  r.stage = "verify";
  r.target = 0;
  r.seed = 5;
  r.inputs = nlohmann::json::object();
  for (std::size_t p = 0; p < study_.parameters.size(); ++p)
    r.inputs[study_.parameters[p].path] = nominal_(static_cast<Eigen::Index>(p));
  const EvaluationRecord plain = evaluate(study_, r, 1, "hash");
  r.out_dir = dir_ + "/scenes/m/contact";
  r.trajectory_interval_s = 1e-5;
  const EvaluationRecord recorded = evaluate(study_, r, 1, "hash");
  ASSERT_EQ(plain.status, "ok") << plain.message;
  ASSERT_EQ(recorded.status, "ok") << recorded.message;
  // The observer reads the simulation only: the same bits.
  EXPECT_EQ(record_metric(study_, recorded), record_metric(study_, plain));
  EXPECT_TRUE(std::filesystem::exists(r.out_dir + "/trajectory.h5"));
  EXPECT_TRUE(std::filesystem::exists(r.out_dir + "/trajectory.xdmf"));
  ASSERT_TRUE(recorded.metrics.contains("trajectory")) << recorded.metrics.dump(1);
  EXPECT_GT(recorded.metrics["trajectory"]["frames"].get<int>(), 1);
  EXPECT_FALSE(plain.metrics.contains("trajectory"));
}

}  // namespace
}  // namespace seedcal
