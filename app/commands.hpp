#pragma once
// Each subcommand of `seedcal` lives in a file of its own and registers itself on the app here.
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "store/version.hpp"

namespace seedcal {

// Options every subcommand shares (DESIGN.md, "Interface").
struct GlobalOptions {
  int threads = 0;  // 0: all cores
  std::uint64_t seed = 1;
  bool seed_given = false;
  int resolved_threads() const;
  // Threads per simulation when `jobs` simulations run at once: one each (a run's CPU time is read
  // from its own thread's clock, solver/scenes/scene_common.hpp); --threads above 1 with more than
  // one job is bad input (InputError).
  int threads_per_job(int jobs) const;
};

// Adds --threads and --seed to a subcommand.
void add_common_options(CLI::App& sub, GlobalOptions& g);

// Each returns nothing; the command's callback throws InputError / RunFailed on failure.
void add_run_command(CLI::App& app, GlobalOptions& g);
void add_clump_command(CLI::App& app, GlobalOptions& g);
void add_doe_command(CLI::App& app, GlobalOptions& g);
void add_calibrate_command(CLI::App& app, GlobalOptions& g);
void add_report_command(CLI::App& app, GlobalOptions& g);
void add_study_command(CLI::App& app, GlobalOptions& g);
void add_bench_command(CLI::App& app, GlobalOptions& g);
void add_export_command(CLI::App& app, GlobalOptions& g);
void add_keys_command(CLI::App& app, GlobalOptions& g);

}  // namespace seedcal
