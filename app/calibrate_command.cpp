// `seedcal calibrate STUDY.toml --out DIR [--resume] [--jobs J] [--threads T] [--set k=v]`: the
// calibration pipeline (docs/calibrate.md). Under mpirun, rank 0 plans and the other ranks run
// the simulations. `seedcal calibrate-worker` is the local worker process it starts itself.
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <unistd.h>

#include "app/commands.hpp"
#include "app/executors/mpi_executor.hpp"
#include "app/executors/worker_pool.hpp"
#include "app/exit_codes.hpp"
#include "calibrate/pipeline/run_study.hpp"
#include "reports/report.hpp"
#include "store/errors.hpp"

namespace seedcal {
namespace {

struct CalibrateArgs {
  StudyRunOptions run;
  bool quiet = false;
  std::string trajectory;  // --trajectory[=verify|confirm|all]
};

// The worker command line for this study: this program's `calibrate-worker`.
WorkerCommand worker_command(const StudyRunOptions& o) {
  WorkerCommand c;
  c.executable = std::filesystem::read_symlink("/proc/self/exe").string();
  c.args = {"calibrate-worker", o.study_file, "--threads", std::to_string(o.threads)};
  for (const auto& s : o.sets) {
    c.args.push_back("--set");
    c.args.push_back(s);
  }
  return c;
}

void calibrate(CalibrateArgs& a, const GlobalOptions& g) {
  refuse_tasks_without_mpi("seedcal calibrate");  // srun without MPI would run the study once per task
  StudyRunOptions o = a.run;
  if (!a.trajectory.empty()) {
    std::string why;
    if (!parse_study_trajectories(a.trajectory, &o.trajectories, &why)) throw InputError("calibrate: " + why);
  }
  o.threads = g.threads > 0 ? g.threads : (MpiSession::size() > 1 ? 1 : std::max(1, g.resolved_threads() / o.jobs));
  if (g.seed_given) o.sets.push_back("seed=" + std::to_string(g.seed));
  if (o.out_dir.empty() && !o.dry_run) throw InputError("calibrate: --out DIR is required");
  if (o.dry_run) {  // the plan and its cost on this machine, nothing run (said once under mpirun)
    if (MpiSession::rank() == 0) run_study(o, {});
    return;
  }
  o.progress_on_terminal = !a.quiet;
  o.render_report = [](const std::string& dir) { reports::render_report(dir); };
  if (MpiSession::size() > 1) {
    if (MpiSession::rank() != 0) {
      const StudyConfig s = read_study(o.study_file, o.sets);
      run_mpi_worker(s, o.threads, study_fingerprint(s));
      return;
    }
    const auto summary = run_study(o, [](const std::string& hash) { return make_mpi_executor(hash); });
    std::cout << summary.dump(2) << "\n";
    return;
  }
  const auto summary = run_study(o, [&o](const std::string& hash) {
    return make_worker_pool(worker_command(o), o.jobs, hash);
  });
  std::cout << summary.dump(2) << "\n";
}

struct WorkerArgs {
  std::string study;
  std::vector<std::string> sets;
};

}  // namespace

void add_calibrate_command(CLI::App& app, GlobalOptions& g) {
  auto a = std::make_shared<CalibrateArgs>();
  CLI::App* sub = app.add_subcommand(
      "calibrate", "fit DEM parameters to laboratory targets: screen, steepest ascent, surrogate, NLopt, confirm");
  sub->add_option("study", a->run.study_file, "study file (TOML), e.g. data/studies/jinong1-quick.toml")->required();
  sub->add_option("--out", a->run.out_dir, "study directory: study.h5, summary.json, calibrate.log (required unless --dry-run)");
  sub->add_flag("--dry-run", a->run.dry_run,
                "print the planned DEM runs and their CPU time on this machine, and run nothing");
  sub->add_flag("--resume", a->run.resume, "continue the study stored in --out (finished runs are not redone)");
  sub->add_flag("--trajectory{verify}", a->trajectory,
                "record trajectories for ParaView (trajectory.h5/.xdmf): =verify (default; the first run of every "
                "verification test under every model), =confirm (the first run of every target at every "
                "confirmation round) or =all");
  sub->add_flag("--force-unlock", a->run.force_unlock,
                "take over the study directory's lock even when another machine holds it (that run must be gone)");
  sub->add_option("--jobs", a->run.jobs, "simulations at once on this machine (worker processes; default 1)")
      ->check(CLI::Range(1, 1024));
  sub->add_option("--set", a->run.sets, "override a study value: key=value (dotted TOML path)");
  sub->add_flag("--quiet", a->quiet, "no progress line on the terminal (the log file is still written)");
  add_common_options(*sub, g);
  sub->callback([a, &g] { calibrate(*a, g); });

  auto w = std::make_shared<WorkerArgs>();
  CLI::App* worker = app.add_subcommand("calibrate-worker", "(internal) run study evaluations read from stdin");
  worker->group("");  // hidden from --help
  worker->add_option("study", w->study, "study file")->required();
  worker->add_option("--set", w->sets, "study overrides");
  add_common_options(*worker, g);
  worker->callback([w, &g] {
    const StudyConfig s = read_study(w->study, w->sets);
    const int rc = run_worker_loop(s, std::max(1, g.threads), study_fingerprint(s), STDIN_FILENO, STDOUT_FILENO);
    // The study process is gone (it ended, was stopped for bad input, or was killed): nobody reads
    // this exit code, and a message would only repeat on the study's terminal.
    if (rc != 0) std::exit(kExitRunFailed);
  });
}

}  // namespace seedcal
