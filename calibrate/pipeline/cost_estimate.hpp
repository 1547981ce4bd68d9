#pragma once
// What a calibration study will cost, said before its first run (`seedcal calibrate`, and all of
// `--dry-run`): the DEM runs each stage plans and the CPU seconds they take on this machine.
//
// A run's cost is its plan's sphere-steps (solver/scenes/run_plan.hpp: the scene's seeds and the
// simulated time of each phase of its protocol) times this machine's CPU seconds per sphere-step,
// measured on a bed of the scene's own seed (solver/scenes/cost_probe.hpp, one probe per
// distinct seed template). The stages' run counts follow the study file: the screening design,
// the surrogate design for the parameters marked `calibrate` (at least two are kept), three
// confirmation rounds of `[confirm] replicates` runs (the budget `max_evaluations` caps it), no
// ascent (it runs only when the screening box misses the target; its most is stated), and every
// verification test under every model.
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "calibrate/pipeline/study_config.hpp"
#include "calibrate/scenes/scene_file.hpp"
#include "solver/scenes/run_plan.hpp"

namespace seedcal {

struct SceneCost {
  std::string test, model, kind;
  RunPlan plan;
  double cpu_s_per_sphere_step = 0.0;
  // Under the stress of its loaded phases (the shear box's consolidation and shear; 0: none), with
  // that stress: those phases are priced at this cost.
  double cpu_s_per_sphere_step_loaded = 0.0, confining_stress_pa = 0.0;
  double cpu_s = 0.0;  // one run
  // Why the scene refuses this model's settings (its runs will fail with that reason and are priced
  // at nothing); empty when the scene accepts them.
  std::string refused;
};

// Prices scene runs on this machine: one cost probe per distinct seed template (at the time step of
// the first scene that uses it: the cost of a step hardly depends on its length), and one more per
// template and stress for the phases a servo loads.
class RunPricer {
 public:
  explicit RunPricer(int threads) : threads_(threads) {}
  // One run of `scene` (its plan and CPU seconds); throws as check_scene does.
  SceneCost price(const SceneFile& scene);
  double probe_cpu_s() const { return probe_cpu_s_; }

 private:
  // One probe per seed template and stress (0: the bed at rest).
  double probe(const RunPlan& plan, double confining_stress_pa);
  int threads_;
  std::map<std::tuple<std::size_t, double, double, double>, double> probes_;  // spheres, mass, radius sum, stress
  double probe_cpu_s_ = 0.0;
};

struct StageRuns {
  std::string stage;
  int runs = 0;      // expected
  int at_most = 0;   // the most it can take
  double cpu_s = 0.0;
  // The expected runs' CPU seconds, batch by batch as the stage hands them to the slots (a batch
  // ends before the next begins: a confirmation round, the curve's points, the verification).
  std::vector<std::vector<double>> batches;
};

// Wall seconds of the stages on `slots` simulations at once: each batch's runs in plan order,
// each to the slot that frees first (list scheduling), batch after batch. A lone long run at a
// batch's end keeps the other slots idle, which CPU seconds over slots would not show; runs side
// by side that slow each other (a shared memory bus) are not priced.
double stages_wall_s(const std::vector<StageRuns>& stages, int slots);

struct StudyCostEstimate {
  std::vector<SceneCost> scenes;  // each target and verification test under each model
  std::vector<StageRuns> stages;
  int runs = 0, runs_at_most = 0;
  double cpu_s = 0.0, cpu_s_at_most = 0.0;
  double probe_cpu_s = 0.0;       // what measuring this machine took
};

// Plans every scene of the study (as check_study_scenes reads them, parameters at nominal) and
// prices it with `threads` threads per simulation. Throws InputError as the scenes' checks do.
StudyCostEstimate estimate_study_cost(const StudyConfig& s, int threads);

// A scene's plan and cost in one line ("plan: ...").
std::string describe_scene_cost(const std::string& what, const SceneCost& c);

// The estimate in lines for the terminal and the log; `slots` simulations run at once.
std::vector<std::string> describe_cost(const StudyCostEstimate& e, int slots);

}  // namespace seedcal
