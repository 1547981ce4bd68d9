#pragma once
// `--jobs J` worker processes on this machine (`seedcal calibrate-worker`), each running one
// simulation at a time with `--threads T`; a simulation that crashes its worker is recorded as
// failed with the signal, and the worker is restarted.
#include <memory>
#include <string>
#include <vector>

#include "calibrate/pipeline/executor.hpp"

namespace seedcal {

struct WorkerCommand {
  std::string executable;          // this program (/proc/self/exe)
  std::vector<std::string> args;   // calibrate-worker STUDY [--set ...] --threads T
};

std::unique_ptr<Executor> make_worker_pool(WorkerCommand command, int jobs,
                                           const std::string& config_hash);

// The worker side: reads one request (JSON) per line from `in_fd`, writes one record (JSON) per
// line to `out_fd`, until end of input.
int run_worker_loop(const StudyConfig& study, int threads, const std::string& config_hash, int in_fd, int out_fd);

}  // namespace seedcal
