// The cluster recipe (docs/cluster.md, scripts/slurm/): the batch scripts parse; a SLURM job step of
// several tasks without MPI is refused by `seedcal calibrate` and `seedcal study` (exit 2, naming
// `srun --mpi=pmix`) while the batch script's own environment is not; calibrate.sbatch runs the
// miniature study (tests/cli/mini/mpi_study.toml, seconds) on two MPI ranks through mpirun and
// through its srun line (a stand-in srun that checks the line and starts mpirun), and a requeued
// job resumes past the lock its previous run left on another node; the array scripts run their
// tasks with the seeds and lines they name.
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "store/study_store.hpp"
#include "tests/support/cli.hpp"

namespace seedcal::testing {
namespace {

// No launcher's variables from the environment the suite runs in (a CI job under SLURM or mpirun).
const std::string kClean =
    "env -u SLURM_JOB_ID -u SLURM_JOBID -u SLURM_NTASKS -u SLURM_NPROCS -u SLURM_PROCID -u SLURM_STEP_ID "
    "-u SLURM_STEPID -u SLURM_STEP_NUM_TASKS -u SLURM_RESTART_COUNT -u SLURM_ARRAY_TASK_ID "
    "-u SLURM_CPUS_PER_TASK -u OMPI_COMM_WORLD_SIZE -u PMI_SIZE -u PMIX_RANK ";

std::string script(const std::string& name) { return source_dir() + "/scripts/slurm/" + name; }
std::string mini_study() { return source_dir() + "/tests/cli/mini/mpi_study.toml"; }

bool have_mpirun() { return std::system("command -v mpirun > /dev/null 2>&1") == 0; }

// mpirun's options for the ranks: under the sanitizers the same as cli_scenes_mini_test's (Open
// MPI's components kept mapped, malloc's callers unwound from DWARF; tests/sanitize/lsan.supp).
std::string mpirun_options() {
  std::string o = "--oversubscribe";
  if (const char* preload = std::getenv("SEEDCAL_MPI_PRELOAD")) {
    const char* asan = std::getenv("ASAN_OPTIONS");
    o += " -x LD_PRELOAD=" + std::string(preload) + " -x ASAN_OPTIONS=" + (asan ? std::string(asan) + ":" : "") +
         "fast_unwind_on_malloc=0";
  }
  return o;
}

TEST(ClusterRecipe, BatchScriptsParse) {
  int scripts = 0;
  for (const auto& f : std::filesystem::directory_iterator(source_dir() + "/scripts/slurm")) {
    if (f.path().extension() != ".sbatch") continue;
    ++scripts;
    const auto r = run_shell("bash -n " + f.path().string() + " 2>&1");
    EXPECT_EQ(r.exit_code, 0) << f.path() << ":\n" << r.output;
  }
  EXPECT_GE(scripts, 3) << "calibrate.sbatch, repeats.sbatch and trends.sbatch";
}

TEST(ClusterRecipe, TaskLaunchWithoutMpiIsRefused) {
  const std::string dir = scratch_dir("cluster-refuse");
  // As srun starts task 1 of a two-task step without a PMI plugin (srun(1), "OUTPUT ENVIRONMENT
  // VARIABLES"); and as an older srun that sets no step variable.
  const std::string srun_step = kClean + "SLURM_JOB_ID=7 SLURM_NTASKS=2 SLURM_PROCID=1 SLURM_STEP_ID=0 SLURM_STEP_NUM_TASKS=2 ";
  const std::string old_srun = kClean + "SLURM_NTASKS=2 SLURM_PROCID=1 ";
  for (const std::string& env : {srun_step, old_srun}) {
    const auto r = run_shell(env + seedcal_binary() + " calibrate " + mini_study() + " --out " + dir +
                             "/out --threads 1 --quiet 2>&1");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("srun --mpi=pmix"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("mpirun"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("task 1 of 2"), std::string::npos) << r.output;
  }
  // `seedcal study` runs in one process: refused under several tasks before it runs anything.
  const auto t = run_shell(srun_step + seedcal_binary() + " study trend --scene " + source_dir() +
                           "/data/scenes/examples/impact.toml --vary materials.glass.youngs_modulus_pa --levels 3e10 1e11 "
                           "--repeats 2 --threads 1 --out " + dir + "/trend 2>&1");
  EXPECT_EQ(t.exit_code, 2) << t.output;
  EXPECT_NE(t.output.find("one task"), std::string::npos) << t.output;
  EXPECT_FALSE(std::filesystem::exists(dir + "/out")) << "a refused calibrate wrote its directory";
  EXPECT_FALSE(std::filesystem::exists(dir + "/trend")) << "a refused study wrote its directory";
  // The batch script itself (sbatch sets SLURM_NTASKS and SLURM_PROCID = 0, no step): one process,
  // not refused.
  const auto b = run_shell(kClean + "SLURM_JOB_ID=7 SLURM_NTASKS=2 SLURM_PROCID=0 " + seedcal_binary() + " calibrate " +
                           mini_study() + " --out " + dir + "/batch --threads 1 --quiet 2>&1");
  EXPECT_EQ(b.exit_code, 0) << b.output;
  std::filesystem::remove_all(dir);
}

TEST(ClusterRecipe, CalibrateScriptRunsOnTwoRanksAndResumesWhenRequeued) {
  if (!have_mpirun()) GTEST_SKIP() << "mpirun not installed";
  const std::string dir = scratch_dir("cluster-sbatch");
  const std::string out = dir + "/study";
  // What sbatch gives the script: two tasks of one CPU each.
  const std::string job = kClean + "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 SLURM_NTASKS=2 "
                          "SLURM_CPUS_PER_TASK=1 SEEDCAL=" + seedcal_binary() + " ";
  const std::string args = " " + mini_study() + " " + out + " 2>&1";

  // 1. Through mpirun: rank 0 plans, rank 1 runs every simulation.
  const auto first = run_shell(job + "SEEDCAL_LAUNCHER=mpirun SEEDCAL_MPIRUN_OPTIONS='" + mpirun_options() +
                               "' bash " + script("calibrate.sbatch") + args);
  ASSERT_EQ(first.exit_code, 0) << first.output;
  const StudyStore store = StudyStore::open(out + "/study.h5");
  ASSERT_FALSE(store.evaluations().empty());
  for (const auto& r : store.evaluations()) EXPECT_EQ(r.metrics.value("mpi_rank", 0), 1) << r.to_json().dump();

  // 2. Through the srun line, with a stand-in srun that accepts only the options the script
  // passes, insists on --mpi=pmix and starts the ranks with mpirun.
  std::filesystem::create_directories(dir + "/bin");
  std::ofstream(dir + "/bin/srun") << "#!/bin/bash\n"
                                      "mpi=; n=\n"
                                      "while [ $# -gt 0 ]; do\n"
                                      "  case $1 in\n"
                                      "    --mpi=*) mpi=${1#--mpi=} ;;\n"
                                      "    --ntasks=*) n=${1#--ntasks=} ;;\n"
                                      "    --cpus-per-task=*) ;;\n"
                                      "    -*) echo \"srun stand-in: unexpected option $1\" >&2; exit 99 ;;\n"
                                      "    *) break ;;\n"
                                      "  esac\n"
                                      "  shift\n"
                                      "done\n"
                                      "[ \"$mpi\" = pmix ] || { echo 'srun stand-in: no --mpi=pmix' >&2; exit 98; }\n"
                                      "exec mpirun " + mpirun_options() + " -n \"$n\" \"$@\"\n";
  std::filesystem::permissions(dir + "/bin/srun", std::filesystem::perms::owner_all, std::filesystem::perm_options::add);
  const std::string srun_job = job + "PATH=" + dir + "/bin:$PATH ";
  // The previous run was killed on another node and left its lock: a plain resubmission is
  // refused (that node cannot be checked from here) and says how to take the lock over.
  std::ofstream(out + "/calibrate.lock") << R"({"host": "node-gone", "pid": 4242, "started_utc": "2020-01-01T00:00:00Z"})" << "\n";
  const auto refused = run_shell(srun_job + "bash " + script("calibrate.sbatch") + args);
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("--force-unlock"), std::string::npos) << refused.output;
  // Requeued by SLURM (SLURM_RESTART_COUNT > 0: the previous run has ended): the script takes the
  // lock over and resumes; every run is answered from the store.
  const auto requeued = run_shell(srun_job + "SLURM_RESTART_COUNT=1 bash " + script("calibrate.sbatch") + args);
  ASSERT_EQ(requeued.exit_code, 0) << requeued.output;
  const auto s = nlohmann::json::parse(read_text(out + "/summary.json"));
  EXPECT_EQ(s["evaluations_from_store"], s["evaluations_total"]) << s.dump(1);
  EXPECT_EQ(s["evaluations_total"].get<std::size_t>(), store.evaluations().size());
  EXPECT_FALSE(std::filesystem::exists(out + "/calibrate.lock")) << "the lock outlived the run";
  std::filesystem::remove_all(dir);
}

TEST(ClusterRecipe, ArrayScriptsRunTheirTasks) {
  const std::string dir = scratch_dir("cluster-array");
  const std::string scene = source_dir() + "/data/scenes/examples/impact.toml";
  const std::string job = kClean + "SLURM_CPUS_PER_TASK=1 SEEDCAL=" + seedcal_binary() + " ";
  // Repeats: task K runs seed SEEDCAL_SEED + K into DIR/repeat-K.
  for (int k : {0, 1}) {
    const auto r = run_shell(job + "SEEDCAL_SEED=5 SLURM_ARRAY_TASK_ID=" + std::to_string(k) + " bash " +
                             script("repeats.sbatch") + " " + scene + " " + dir + "/repeats > /dev/null 2>" + dir + "/err");
    ASSERT_EQ(r.exit_code, 0) << read_text(dir + "/err");
    const auto m = nlohmann::json::parse(read_text(dir + "/repeats/repeat-" + std::to_string(k) + "/metrics.json"));
    EXPECT_EQ(m["provenance"]["seed"], 5 + k);
    EXPECT_EQ(m["repeats"], 1);
  }
  // Trends: task K runs line K of the list (comments and blank lines skipped) into DIR/trend-K.
  std::ofstream(dir + "/trends.txt") << "# one trend check a line\n\n--scene " << scene
                                     << " --vary materials.glass.youngs_modulus_pa --levels 3e10 1e11 --expect fall "
                                        "--metric contact_duration_s --repeats 2\n";
  const auto t = run_shell(job + "SLURM_ARRAY_TASK_ID=1 bash " + script("trends.sbatch") + " " + dir + "/trends.txt " +
                           dir + "/trends > /dev/null 2>" + dir + "/err");
  ASSERT_EQ(t.exit_code, 0) << read_text(dir + "/err");
  const auto j = nlohmann::json::parse(read_text(dir + "/trends/trend-1/trend.json"));
  EXPECT_EQ(j["levels"].size(), 2u) << j.dump(1);
  const auto none = run_shell(job + "SLURM_ARRAY_TASK_ID=2 bash " + script("trends.sbatch") + " " + dir +
                              "/trends.txt " + dir + "/trends 2>&1");
  EXPECT_EQ(none.exit_code, 2) << none.output;
  EXPECT_NE(none.output.find("no check 2"), std::string::npos) << none.output;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace seedcal::testing
