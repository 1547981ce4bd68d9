#include "app/executors/mpi_executor.hpp"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <thread>
#include <deque>
#include <string>

#include "store/errors.hpp"

#ifdef SEEDCAL_HAVE_MPI
#include <mpi.h>
#endif

namespace seedcal {
namespace {

bool launched_by_mpi() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
    if (std::getenv(v)) return true;
  return false;
}

// An environment variable as a whole number, or -1 when unset or not a number.
long env_number(const char* name) {
  const char* v = std::getenv(name);
  if (!v || !*v) return -1;
  char* end = nullptr;
  const long n = std::strtol(v, &end, 10);
  return *end == '\0' ? n : -1;
}

// The tasks of the SLURM job step this process is one of; 0 outside a step. srun sets
// SLURM_STEP_NUM_TASKS for the step (and SLURM_NTASKS, SLURM_PROCID, SLURM_STEP_ID); sbatch gives
// the batch script SLURM_NTASKS and SLURM_PROCID = 0 of the allocation but no step variables
// (Slurm's srun(1) and sbatch(1), "OUTPUT ENVIRONMENT VARIABLES"). A task numbered above 0 is in
// a step even where an older srun set no step variable.
long slurm_step_tasks() {
  const long step = env_number("SLURM_STEP_NUM_TASKS");
  if (step >= 0) return step;
  if (std::getenv("SLURM_STEP_ID") || std::getenv("SLURM_STEPID") || env_number("SLURM_PROCID") > 0)
    return std::max(0L, env_number("SLURM_NTASKS"));
  return 0;
}

std::string task_text() {
  const long rank = env_number("SLURM_PROCID");
  return (rank >= 0 ? "task " + std::to_string(rank) + " of " : "one of ") + std::to_string(slurm_step_tasks()) +
         " tasks of a SLURM job step";
}

#ifdef SEEDCAL_HAVE_MPI
constexpr int kTagRequest = 1, kTagRecord = 2, kTagStop = 3;

std::string receive(int source, int tag, MPI_Status* status) {
  MPI_Status probe;
  MPI_Probe(source, tag, MPI_COMM_WORLD, &probe);
  int n = 0;
  MPI_Get_count(&probe, MPI_CHAR, &n);
  std::string s(static_cast<std::size_t>(n), '\0');
  MPI_Recv(s.data(), n, MPI_CHAR, probe.MPI_SOURCE, probe.MPI_TAG, MPI_COMM_WORLD, status);
  return s;
}

void send(const std::string& s, int dest, int tag) {
  MPI_Send(s.data(), static_cast<int>(s.size()), MPI_CHAR, dest, tag, MPI_COMM_WORLD);
}

class MpiExecutor final : public Executor {
 public:
  explicit MpiExecutor(std::string hash) : hash_(std::move(hash)) {
    if (MpiSession::size() < 2) throw InputError("the MPI backend needs at least 2 ranks (rank 0 plans, the others run)");
  }
  ~MpiExecutor() override {
    for (int r = 1; r < MpiSession::size(); ++r) send("stop", r, kTagStop);
  }
  int slots() const override { return MpiSession::size() - 1; }
  std::string describe() const override { return std::to_string(slots()) + " MPI worker rank(s)"; }
  void run(const std::vector<EvalRequest>& requests, const RecordCallback& done, const DispatchCheck& check) override {
    std::deque<std::size_t> queue;
    for (std::size_t i = 0; i < requests.size(); ++i) queue.push_back(i);
    std::vector<long> busy(static_cast<std::size_t>(MpiSession::size()), -1);
    std::size_t finished = 0;
    while (finished < requests.size()) {
      for (int r = 1; r < MpiSession::size(); ++r) {
        if (busy[static_cast<std::size_t>(r)] >= 0) continue;
        finished += skip_unneeded(queue, check, done);
        if (queue.empty()) break;
        busy[static_cast<std::size_t>(r)] = static_cast<long>(queue.front());
        send(requests[queue.front()].to_json().dump(), r, kTagRequest);
        queue.pop_front();
      }
      finished += skip_unneeded(queue, check, done);
      bool running = false;
      for (const long b : busy) running = running || b >= 0;
      if (!running) continue;  // everything left was skipped, or is queued for a free rank
      // Poll politely: a blocking receive spins a core that a worker rank on this node could use.
      for (int flag = 0; !flag;) {
        MPI_Iprobe(MPI_ANY_SOURCE, kTagRecord, MPI_COMM_WORLD, &flag, MPI_STATUS_IGNORE);
        if (!flag) std::this_thread::sleep_for(std::chrono::milliseconds(2));
      }
      MPI_Status status;
      const std::string text = receive(MPI_ANY_SOURCE, kTagRecord, &status);
      const auto i = static_cast<std::size_t>(busy[static_cast<std::size_t>(status.MPI_SOURCE)]);
      busy[static_cast<std::size_t>(status.MPI_SOURCE)] = -1;
      EvaluationRecord rec = EvaluationRecord::from_json(nlohmann::json::parse(text));
      rec.metrics["mpi_rank"] = status.MPI_SOURCE;
      done(i, std::move(rec));
      ++finished;
    }
  }

 private:
  std::string hash_;
};
#endif

}  // namespace

void refuse_tasks_without_mpi(const std::string& command) {
  if (launched_by_mpi() || slurm_step_tasks() <= 1) return;
  throw InputError(
      command + ": started as " + task_text() + " without MPI (none of OMPI_COMM_WORLD_SIZE, PMI_SIZE, "
      "PMIX_RANK is set), so every task would run the whole study by itself. Start the ranks through MPI: "
      "`srun --mpi=pmix " + command + " ...` (`srun --mpi=list` names the plugins the cluster has) or "
      "`mpirun -n N " + command + " ...` inside the allocation; or run one task (`srun -n 1`) with --jobs "
      "for the simulations at once (docs/cluster.md, scripts/slurm/calibrate.sbatch)");
}

void refuse_several_tasks(const std::string& command) {
  std::string launch;
  if (slurm_step_tasks() > 1 && !launched_by_mpi()) launch = task_text();
  else if (MpiSession::size() > 1) launch = "one of " + std::to_string(MpiSession::size()) + " MPI ranks";
  else return;
  throw InputError(command + ": started as " + launch + ", but it runs in one process, so every task would run "
                   "the whole study by itself. Run it as one task (`srun -n 1`, with --jobs or --threads for "
                   "the cores), and spread independent studies over a job array (docs/cluster.md, "
                   "scripts/slurm/)");
}

#ifdef SEEDCAL_HAVE_MPI
MpiSession::MpiSession(int* argc, char*** argv) {
  if (!launched_by_mpi()) return;
  int provided = 0;
  MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided);
  active_ = true;
}
MpiSession::~MpiSession() {
  if (active_) MPI_Finalize();
}
namespace {
// MPI_Comm_rank / MPI_Comm_size of the world, or `fallback` when MPI is not initialised.
int world_query(int (*query)(MPI_Comm, int*), int fallback) {
  int init = 0;
  MPI_Initialized(&init);
  int v = fallback;
  if (init) query(MPI_COMM_WORLD, &v);
  return v;
}
}  // namespace
int MpiSession::rank() { return world_query(MPI_Comm_rank, 0); }
int MpiSession::size() { return world_query(MPI_Comm_size, 1); }
std::unique_ptr<Executor> make_mpi_executor(const std::string& config_hash) {
  return std::make_unique<MpiExecutor>(config_hash);
}
void run_mpi_worker(const StudyConfig& study, int threads, const std::string& config_hash) {
  for (;;) {
    MPI_Status status;
    MPI_Probe(0, MPI_ANY_TAG, MPI_COMM_WORLD, &status);
    const std::string text = receive(0, status.MPI_TAG, &status);
    if (status.MPI_TAG == kTagStop) return;
    const EvalRequest req = EvalRequest::from_json(nlohmann::json::parse(text));
    send(evaluate(study, req, threads, config_hash).to_json().dump(), 0, kTagRecord);
  }
}
#else
MpiSession::MpiSession(int*, char***) {
  if (launched_by_mpi())
    throw InputError("started by an MPI launcher, but this seedcal was built without MPI (install libopenmpi-dev and rebuild)");
}
MpiSession::~MpiSession() = default;
int MpiSession::rank() { return 0; }
int MpiSession::size() { return 1; }
std::unique_ptr<Executor> make_mpi_executor(const std::string&) {
  throw InputError("this seedcal was built without MPI");
}
void run_mpi_worker(const StudyConfig&, int, const std::string&) {}
#endif

}  // namespace seedcal
