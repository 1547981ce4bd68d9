// Local worker processes for `seedcal calibrate --jobs J` (worker_pool.hpp). A process per slot,
// not a thread: each simulation's CPU time is its own process's, and a simulation that crashes
// (a signal) takes down only its worker, never the study. Pipe ends are close-on-exec, so a worker
// never holds another worker's pipe open (each sees end of input when the study closes its pipe).
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <deque>
#include <fcntl.h>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include "app/executors/worker_pool.hpp"
#include "store/errors.hpp"
#include "store/version.hpp"

namespace seedcal {
namespace {

// Writes all of `s` (retrying short writes and EINTR); false when the other end is gone.
bool write_all(int fd, const std::string& s) {
  std::size_t off = 0;
  while (off < s.size()) {
    const ssize_t n = ::write(fd, s.data() + off, s.size() - off);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    off += static_cast<std::size_t>(n);
  }
  return true;
}

struct Worker {
  pid_t pid = -1;
  int to_fd = -1;    // the worker's stdin
  int from_fd = -1;  // the worker's stdout
  std::string buffer;
  long busy_with = -1;  // request index, -1 when idle
};

class WorkerPool final : public Executor {
 public:
  WorkerPool(WorkerCommand command, int jobs, std::string config_hash)
      : command_(std::move(command)), config_hash_(std::move(config_hash)), workers_(static_cast<std::size_t>(jobs)) {
    std::signal(SIGPIPE, SIG_IGN);  // a dead worker's pipe is noticed by poll, not by a signal
  }
  ~WorkerPool() override {
    for (auto& w : workers_) stop(w);
  }
  int slots() const override { return static_cast<int>(workers_.size()); }
  std::string describe() const override {
    return std::to_string(workers_.size()) + " worker process" + (workers_.size() == 1 ? "" : "es");
  }

  void run(const std::vector<EvalRequest>& requests, const RecordCallback& done, const DispatchCheck& check) override {
    std::deque<std::size_t> queue;
    for (std::size_t i = 0; i < requests.size(); ++i) queue.push_back(i);
    std::size_t finished = 0;
    while (finished < requests.size()) {
      for (auto& w : workers_) {
        if (w.busy_with >= 0) continue;
        finished += skip_unneeded(queue, check, done);
        if (queue.empty()) continue;
        if (w.pid < 0) start(w);
        const std::size_t i = queue.front();
        queue.pop_front();
        const std::string line = requests[i].to_json().dump() + "\n";
        w.busy_with = static_cast<long>(i);
        if (!write_all(w.to_fd, line)) {  // died while idle: record it against this request
          finish_dead(w, requests, done);
          ++finished;
        }
      }
      finished += skip_unneeded(queue, check, done);
      std::vector<pollfd> fds;
      std::vector<Worker*> who;
      for (auto& w : workers_)
        if (w.busy_with >= 0) {
          fds.push_back({w.from_fd, POLLIN, 0});
          who.push_back(&w);
        }
      if (fds.empty()) continue;
      const int rc = ::poll(fds.data(), fds.size(), -1);
      if (rc < 0) {
        if (errno == EINTR) continue;
        throw RunFailed(std::string("waiting for the worker processes: ") + std::strerror(errno));
      }
      for (std::size_t k = 0; k < fds.size(); ++k) {
        if (!(fds[k].revents & (POLLIN | POLLHUP | POLLERR))) continue;
        Worker& w = *who[k];
        char buf[65536];
        const ssize_t n = ::read(w.from_fd, buf, sizeof buf);
        if (n > 0) {
          w.buffer.append(buf, static_cast<std::size_t>(n));
          const auto nl = w.buffer.find('\n');
          if (nl == std::string::npos) continue;
          const std::string line = w.buffer.substr(0, nl);
          w.buffer.erase(0, nl + 1);
          const std::size_t i = static_cast<std::size_t>(w.busy_with);
          w.busy_with = -1;
          EvaluationRecord rec;
          try {
            rec = EvaluationRecord::from_json(nlohmann::json::parse(line));
          } catch (const std::exception& e) {
            rec = failed_record(requests[i], std::string("unreadable answer from a worker: ") + e.what());
          }
          done(i, std::move(rec));
          ++finished;
        } else if (n == 0 || (errno != EINTR && errno != EAGAIN)) {
          finish_dead(w, requests, done);
          ++finished;
        }
      }
    }
  }

 private:
  EvaluationRecord failed_record(const EvalRequest& r, const std::string& why) const {
    EvaluationRecord rec;
    rec.stage = r.stage;
    rec.inputs = r.inputs;
    rec.seed = r.seed;
    rec.metrics = {{"study_target", r.target}};
    rec.status = "failed";
    rec.message = why;
    rec.config_hash = config_hash_;
    rec.seedcal_version = version_string();
    return rec;
  }

  void finish_dead(Worker& w, const std::vector<EvalRequest>& requests, const RecordCallback& done) {
    const std::size_t i = static_cast<std::size_t>(w.busy_with);
    int status = 0;
    std::string why = "the worker process ended while running this simulation";
    if (w.pid > 0 && ::waitpid(w.pid, &status, 0) == w.pid) {
      if (WIFSIGNALED(status)) why += " (signal " + std::to_string(WTERMSIG(status)) + ": " + strsignal(WTERMSIG(status)) + ")";
      else if (WIFEXITED(status)) why += " (exit code " + std::to_string(WEXITSTATUS(status)) + ")";
    }
    w.pid = -1;
    ::close(w.to_fd);
    ::close(w.from_fd);
    w.to_fd = w.from_fd = -1;
    w.buffer.clear();
    w.busy_with = -1;
    done(i, failed_record(requests[i], why));
  }

  void start(Worker& w) {
    int in[2], out[2];
    if (::pipe2(in, O_CLOEXEC) != 0 || ::pipe2(out, O_CLOEXEC) != 0) throw RunFailed(std::string("cannot create a pipe: ") + std::strerror(errno));
    std::vector<std::string> argv_s = {command_.executable};
    argv_s.insert(argv_s.end(), command_.args.begin(), command_.args.end());
    std::vector<char*> argv;
    for (auto& a : argv_s) argv.push_back(a.data());
    argv.push_back(nullptr);
    const pid_t parent = ::getpid();
    const pid_t pid = ::fork();
    if (pid < 0) throw RunFailed(std::string("cannot start a worker process: ") + std::strerror(errno));
    if (pid == 0) {
      ::prctl(PR_SET_PDEATHSIG, SIGKILL);  // a killed study takes its workers with it
      if (::getppid() != parent) ::_exit(127);
      ::dup2(in[0], STDIN_FILENO);
      ::dup2(out[1], STDOUT_FILENO);
      ::close(in[0]); ::close(in[1]); ::close(out[0]); ::close(out[1]);
      ::execv(argv[0], argv.data());
      ::_exit(127);
    }
    ::close(in[0]);
    ::close(out[1]);
    w.pid = pid;
    w.to_fd = in[1];
    w.from_fd = out[0];
  }

  void stop(Worker& w) {
    if (w.pid < 0) return;
    ::close(w.to_fd);  // end of input: the worker returns
    ::close(w.from_fd);
    int status = 0;
    ::waitpid(w.pid, &status, 0);
    w.pid = -1;
  }

  WorkerCommand command_;
  std::string config_hash_;
  std::vector<Worker> workers_;
};

}  // namespace

std::unique_ptr<Executor> make_worker_pool(WorkerCommand command, int jobs, const std::string& config_hash) {
  return std::make_unique<WorkerPool>(std::move(command), jobs, config_hash);
}

int run_worker_loop(const StudyConfig& study, int threads, const std::string& config_hash, int in_fd, int out_fd) {
  std::string buffer;
  char buf[65536];
  for (;;) {
    auto nl = buffer.find('\n');
    while (nl == std::string::npos) {
      const ssize_t n = ::read(in_fd, buf, sizeof buf);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) return 0;
      buffer.append(buf, static_cast<std::size_t>(n));
      nl = buffer.find('\n');
    }
    const std::string line = buffer.substr(0, nl);
    buffer.erase(0, nl + 1);
    const EvalRequest req = EvalRequest::from_json(nlohmann::json::parse(line));
    if (!write_all(out_fd, evaluate(study, req, threads, config_hash).to_json().dump() + "\n")) return 1;
  }
}

}  // namespace seedcal
