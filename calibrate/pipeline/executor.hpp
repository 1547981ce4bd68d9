#pragma once
// Where a batch of DEM evaluations runs. The planner hands a batch to an executor and gets each
// record back as soon as its simulation ends (in the planner's thread, so the store is appended
// to in one place).
// The executors live with the program (app/executors/): worker processes on this machine
// (worker_pool.hpp) and the ranks of an MPI job (mpi_executor.hpp).
#include <cstddef>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "calibrate/pipeline/evaluation.hpp"

namespace seedcal {

using RecordCallback = std::function<void(std::size_t index, EvaluationRecord record)>;
// Asked just before request `index` is handed to a simulation slot: a record to report instead of
// running it (a run the study no longer needs), or nothing to run it.
using DispatchCheck = std::function<std::optional<EvaluationRecord>(std::size_t index)>;

// Reports the queue's leading requests that `check` answers instead of a simulation (popped, and
// their records passed to `done`); returns how many.
inline std::size_t skip_unneeded(std::deque<std::size_t>& queue, const DispatchCheck& check, const RecordCallback& done) {
  std::size_t skipped = 0;
  while (check && !queue.empty()) {
    std::optional<EvaluationRecord> instead = check(queue.front());
    if (!instead) break;
    const std::size_t i = queue.front();
    queue.pop_front();
    done(i, std::move(*instead));
    ++skipped;
  }
  return skipped;
}

class Executor {
 public:
  virtual ~Executor() = default;
  virtual int slots() const = 0;  // simulations that run at once
  virtual std::string describe() const = 0;
  virtual void run(const std::vector<EvalRequest>& requests, const RecordCallback& done,
                   const DispatchCheck& check = {}) = 0;
};

// Makes the executor of a study from its fingerprint (the workers check that they run the same
// study): the app's worker pool or MPI executor (app/executors/).
using ExecutorFactory = std::function<std::unique_ptr<Executor>(const std::string& config_hash)>;

}  // namespace seedcal
