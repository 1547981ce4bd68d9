#pragma once
// MPI backend (`mpirun -n N seedcal calibrate ...`): rank 0 plans and writes the store, ranks
// 1..N-1 run one simulation at a time each. Messages are the JSON texts of a request (rank 0 ->
// worker, tag 1), a record (worker -> rank 0, tag 2) and "stop" (tag 3). Built when CMake finds
// MPI (SEEDCAL_HAVE_MPI); MPI is initialised only when the process was started by an MPI launcher.
#include <memory>
#include <string>

#include "calibrate/pipeline/executor.hpp"

namespace seedcal {

// Initialises MPI when launched by mpirun (OMPI_COMM_WORLD_SIZE / PMI_SIZE set) and finalises it
// on destruction; a no-op otherwise or when built without MPI.
class MpiSession {
 public:
  MpiSession(int* argc, char*** argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  static int rank();  // 0 when not under MPI
  static int size();  // 1 when not under MPI
 private:
  bool active_ = false;
};

// Refuses (InputError, exit 2) a launch that would run `command` once per task: a SLURM job step
// of several tasks (`srun -n N`) that no MPI launcher started. srun starts MPI only through a PMI
// plugin (`srun --mpi=pmix`); without one (`--mpi=none`, or a cluster whose default plugin is
// none) every task would run the whole study by itself. The tasks of the step are
// SLURM_STEP_NUM_TASKS (srun sets it, SLURM_NTASKS when an older srun does not); the batch
// script itself is in no step (sbatch sets no step variable there), so `seedcal calibrate --jobs J`
// called in the script is not refused. An MPI launch (OMPI_COMM_WORLD_SIZE, PMI_SIZE or PMIX_RANK set) is not refused.
void refuse_tasks_without_mpi(const std::string& command);

// Refuses a launch of several tasks of any kind (an srun step or MPI ranks) for a command that
// runs in one process (`seedcal study`): each task would run it whole.
void refuse_several_tasks(const std::string& command);

// Rank 0's executor over ranks 1..size-1; sends "stop" to every worker when destroyed.
std::unique_ptr<Executor> make_mpi_executor(const std::string& config_hash);

// Ranks 1..N-1: answer requests until "stop".
void run_mpi_worker(const StudyConfig& study, int threads, const std::string& config_hash);

}  // namespace seedcal
