// The cost estimate of `seedcal calibrate --dry-run` (cost_estimate.hpp) on the shipped quick
// study: its run count follows the study's plan, every scene is priced from its own plan, and the
// lines say what the command prints. Its agreement with a measured study is in
// docs/results/cost_estimate.md (a timing, not a test); the plans' agreement with the steps runs
// take is checked by the regression tests (tests/support/scene_runs.hpp).
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "calibrate/output/run_progress_line.hpp"
#include "calibrate/pipeline/cost_estimate.hpp"
#include "calibrate/pipeline/progress.hpp"
#include "calibrate/pipeline/study_config.hpp"
#include "calibrate/scenes/scene_file.hpp"
#include "solver/scenes/cost_probe.hpp"
#include "tests/support/cli.hpp"

namespace seedcal {
namespace {

const StageRuns& stage(const StudyCostEstimate& e, const std::string& name) {
  for (const StageRuns& r : e.stages)
    if (r.stage == name) return r;
  ADD_FAILURE() << "no stage " << name;
  static const StageRuns none;
  return none;
}

TEST(CostEstimate, QuickStudyRunsFollowItsPlan) {
  const StudyConfig s = read_study(testing::source_dir() + "/data/studies/jinong1-quick.toml");
  const StudyCostEstimate e = estimate_study_cost(s, 1);
  const int targets = static_cast<int>(s.targets.size());
  // One priced scene per test per model.
  ASSERT_EQ(e.scenes.size(), s.models.size() * static_cast<std::size_t>(s.scene_count()));
  for (const SceneCost& c : e.scenes) {
    SCOPED_TRACE(c.test + " / " + c.model);
    EXPECT_TRUE(c.refused.empty()) << c.refused;
    EXPECT_GT(c.plan.seeds, 1.0);
    EXPECT_GT(c.plan.spheres, c.plan.seeds);  // multi-sphere clumps
    EXPECT_GT(c.plan.steps(), 0.0);
    EXPECT_GT(c.cpu_s_per_sphere_step, 0.0);
    // The phases a servo loads (the shear box's consolidation and shear) at the loaded probe's
    // cost, the others at the bed's at rest.
    double loaded = 0.0, at_rest = 0.0;
    for (const PlanPhase& ph : c.plan.phases)
      (ph.confining_stress_pa > 0.0 ? loaded : at_rest) += ph.spheres * ph.simulated_s / c.plan.dt_s;
    EXPECT_EQ(loaded > 0.0, c.kind == "direct_shear");
    EXPECT_EQ(c.cpu_s_per_sphere_step_loaded > 0.0, loaded > 0.0);
    if (loaded > 0.0) {
      EXPECT_EQ(c.confining_stress_pa, 2e5);  // the quick box's normal stress
    }
    EXPECT_NEAR(c.cpu_s, at_rest * c.cpu_s_per_sphere_step + loaded * c.cpu_s_per_sphere_step_loaded, 1e-12 * c.cpu_s);
  }
  // The stages as the study file sets them: the screening design with its replicates, no ascent
  // expected, the heap at the curve's points, the verification's every test under every model with
  // its replicates but the heap under the first model (its runs along the curve serve).
  EXPECT_EQ(stage(e, "screening").runs, s.screen.runs * s.screen.replicates * targets);
  EXPECT_EQ(stage(e, "ascent").runs, 0);
  EXPECT_EQ(stage(e, "ascent").at_most, s.ascent.max_steps * s.screen.replicates * targets);
  ASSERT_EQ(s.verify.curve_test, "piling");
  EXPECT_EQ(stage(e, "curve").runs, s.verify.curve_points);
  int verify = 0, heap_first_model = 0;
  for (std::size_t m = 0; m < s.models.size(); ++m)
    for (int t = 0; t < s.scene_count(); ++t) {
      const StudyTarget& test = s.scene_of(t);
      const int reps = test.replicates > 0 && t >= targets ? test.replicates : s.verify.replicates;
      verify += reps;
      if (m == 0 && test.name == "piling") heap_first_model = reps;
    }
  EXPECT_EQ(stage(e, "verification").runs, verify - heap_first_model);
  EXPECT_EQ(stage(e, "verification").at_most, verify);
  int sum = 0;
  double cpu = 0.0;
  for (const StageRuns& r : e.stages) {
    EXPECT_LE(r.runs, r.at_most) << r.stage;
    sum += r.runs;
    cpu += r.cpu_s;
  }
  EXPECT_EQ(e.runs, sum);
  EXPECT_NEAR(e.cpu_s, cpu, 1e-9 * cpu);
  EXPECT_LE(e.runs, e.runs_at_most);
  EXPECT_LE(e.cpu_s, e.cpu_s_at_most * (1.0 + 1e-12));
  // Each stage's batches hold its expected runs and their CPU seconds; on two slots the wall time
  // lies between half the CPU time (every slot busy throughout) and all of it.
  for (const StageRuns& r : e.stages) {
    std::size_t runs = 0;
    double batch_cpu = 0.0;
    for (const auto& b : r.batches) {
      runs += b.size();
      for (const double c : b) batch_cpu += c;
    }
    EXPECT_EQ(runs, static_cast<std::size_t>(r.runs)) << r.stage;
    EXPECT_NEAR(batch_cpu, r.cpu_s, 1e-9 * (1.0 + r.cpu_s)) << r.stage;
  }
  const double wall = stages_wall_s(e.stages, 2);
  EXPECT_GE(wall, 0.5 * e.cpu_s * (1.0 - 1e-12));
  EXPECT_LE(wall, e.cpu_s * (1.0 + 1e-12));
  const auto lines = describe_cost(e, 2);
  ASSERT_FALSE(lines.empty());
  EXPECT_NE(lines.back().find("plan: in all ~" + std::to_string(e.runs) + " DEM runs"), std::string::npos)
      << lines.back();
  EXPECT_NE(lines.back().find("on 2 slots"), std::string::npos) << lines.back();
  // A heap of some eight hundred seeds, poured and settled for seconds, costs more than the shear
  // box's hundred seeds in under a second.
  double shear = 0.0, heap = 0.0;
  for (const SceneCost& c : e.scenes) {
    if (c.kind == "piling") heap = c.cpu_s;
    if (c.kind == "direct_shear") shear = c.cpu_s;
  }
  EXPECT_GT(heap, 10.0 * shear);
}

// The loaded probe presses its bed to the stress asked (to the servo's 5 % tolerance, with the
// bed's own settling on top: 10 %) with at least 160 bodies, two to three seeds deep; the bed at
// rest has no lid.
TEST(CostProbe, LoadedBedHoldsItsStress) {
  const StudyConfig s = read_study(testing::source_dir() + "/data/studies/jinong1-quick.toml");
  const StudyTarget& shear = s.scene_of(0);
  ASSERT_EQ(shear.name, "shear");
  const RunPlan plan = plan_scene(load_scene_file(shear.scene, {"fidelity=quick"}));
  const CostProbe loaded = probe_sphere_step_cost(plan.physics, plan.body, plan.dt_s, 1, true, 2e5);
  EXPECT_GE(loaded.bodies, 160u);
  EXPECT_EQ(loaded.confining_stress_pa, 2e5);
  EXPECT_NEAR(loaded.measured_stress_pa / 2e5, 1.0, 0.10);
  EXPECT_GT(loaded.cpu_s_per_sphere_step, 0.0);
  const CostProbe rest = probe_sphere_step_cost(plan.physics, plan.body, plan.dt_s, 1, true);
  EXPECT_EQ(rest.measured_stress_pa, 0.0);
}

// List scheduling batch by batch: a batch ends when its last run does, and the next starts then.
TEST(CostEstimate, WallTimeSchedulesEachBatchOnTheSlots) {
  StageRuns even{"even", 3, 3, 30.0, {{10.0, 10.0, 10.0}}};
  EXPECT_EQ(stages_wall_s({even}, 2), 20.0);  // two at once, then the third alone
  EXPECT_EQ(stages_wall_s({even}, 3), 10.0);
  EXPECT_EQ(stages_wall_s({even}, 1), 30.0);
  // A long run with short ones beside it: the long one sets the batch's time.
  StageRuns tail{"tail", 4, 4, 315.0, {{5.0, 5.0, 300.0, 5.0}}};
  EXPECT_EQ(stages_wall_s({tail}, 2), 305.0);  // 5 | 5, then 300 beside 5
  // Rounds one after another: {4, 4} then {4, 4, 4} on two slots is 4 + 8.
  StageRuns rounds{"rounds", 5, 5, 20.0, {{4.0, 4.0}, {4.0, 4.0, 4.0}}};
  EXPECT_EQ(stages_wall_s({rounds, tail}, 2), 12.0 + 305.0);
  EXPECT_EQ(stages_wall_s({}, 2), 0.0);
}

TEST(CostEstimate, ARefusedSceneIsNamedAndPricedAtNothing) {
  SceneCost c;
  c.kind = "impact";
  c.refused = "impact.toml: dt_s: = 1e-05 s is above the stable limit\n";
  const std::string line = describe_scene_cost("test \"t\" under model \"m\"", c);
  EXPECT_NE(line.find("refused by the scene"), std::string::npos) << line;
  EXPECT_NE(line.find("dt_s: = 1e-05 s is above the stable limit"), std::string::npos) << line;
  EXPECT_EQ(line.find('\n'), std::string::npos) << line;
}

TEST(CostEstimate, ClockText) {
  EXPECT_EQ(clock_text(0.0), "0:00:00");
  EXPECT_EQ(clock_text(59.6), "0:01:00");
  EXPECT_EQ(clock_text(3 * 3600 + 25 * 60 + 7), "3:25:07");
  EXPECT_EQ(clock_text(-5.0), "?");  // unknown
}

TEST(RunProgressLine, FormatSaysWhatIsNotYetKnown) {
  const std::string line = RunProgressLine::format(1, 4, 0.123, 0.35, 747, 2.5e4, 61.0, 125.0);
  EXPECT_EQ(line, "run 2/4: t = 0.123 of ~0.35 s simulated, 747 spheres, 25000 steps/s, elapsed 0:01:01, left ~0:02:05");
  const std::string start = RunProgressLine::format(0, 1, 0.0, 0.35, 9, 0.0, 0.0, -1.0);
  EXPECT_NE(start.find("measuring steps/s"), std::string::npos) << start;
  EXPECT_NE(start.find("left ~?"), std::string::npos) << start;
}

}  // namespace
}  // namespace seedcal
