// seedcal: calibrates DEM models of seeds. One binary, subcommands (DESIGN.md, "Interface").
#include <iostream>
#include <string>
#include <thread>

#include "app/commands.hpp"
#include "app/executors/mpi_executor.hpp"
#include "app/exit_codes.hpp"
#include "store/errors.hpp"

namespace seedcal {

int GlobalOptions::resolved_threads() const {
  if (threads > 0) return threads;
  const unsigned n = std::thread::hardware_concurrency();
  return n > 0 ? static_cast<int>(n) : 1;
}

int GlobalOptions::threads_per_job(int jobs) const {
  if (jobs <= 1) return resolved_threads();
  if (threads > 1)
    throw InputError("--threads = " + std::to_string(threads) + " with --jobs = " + std::to_string(jobs) +
                     ": simulations run at once are one thread each (allowed: --threads 1), so that each "
                     "run's CPU time is its own");
  return 1;
}

void add_common_options(CLI::App& sub, GlobalOptions& g) {
  sub.add_option("--threads", g.threads, "OpenMP threads per simulation (default: all cores)")
      ->check(CLI::Range(1, 4096));
  sub.add_option_function<std::uint64_t>(
         "--seed", [&g](const std::uint64_t& s) { g.seed = s; g.seed_given = true; },
         "random seed (default 1)");
}

}  // namespace seedcal

int main(int argc, char** argv) {
  using namespace seedcal;
  CLI::App app{"seedcal: calibrate discrete element models of seeds (multi-sphere clumps, "
               "Hertz-Mindlin DEM, designs of experiments and surrogates)"};
  app.set_version_flag("--version", version_string());
  app.require_subcommand(1);
  GlobalOptions g;
  add_run_command(app, g);
  add_clump_command(app, g);
  add_doe_command(app, g);
  add_calibrate_command(app, g);
  add_report_command(app, g);
  add_study_command(app, g);
  add_bench_command(app, g);
  add_export_command(app, g);
  add_keys_command(app, g);
  try {
    MpiSession mpi(&argc, &argv);  // only when started by mpirun
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? kExitOk : kExitBadInput;
  } catch (const InputError& e) {
    std::cerr << "seedcal: bad input:\n" << e.what() << "\n";
    return kExitBadInput;
  } catch (const RunFailed& e) {
    std::cerr << "seedcal: run failed: " << e.what() << "\n";
    return kExitRunFailed;
  } catch (const std::exception& e) {
    std::cerr << "seedcal: internal error: " << e.what() << "\n";
    return kExitRunFailed;
  }
  return kExitOk;
}
