#pragma once
// One `seedcal calibrate` at a time on a study directory. Two runs of one study (a cluster job
// requeued while the first still runs, `--resume` in a second terminal) would both rewrite
// study.h5 and summary.json; the second could also repeat the first's simulations. The lock is the
// file DIR/calibrate.lock, created with O_CREAT | O_EXCL (atomic on a local file system), holding
// the owner's host, pid and start time as JSON.
//   - A lock held by a live process refuses the run: InputError (exit 2) naming host and pid.
//   - A lock whose process is gone on this host (kill(pid, 0) fails with ESRCH) is taken over,
//     with a warning: a crashed or killed run left it.
//   - A lock from another host cannot be checked from here: refused unless force_unlock, and the
//     message says to pass --force-unlock once that run is known to be gone.
// The lock is released (the file removed) when the object goes out of scope.
#include <string>
#include <vector>

namespace seedcal {

class StudyLock {
 public:
  // Throws InputError when the directory is held; appends a line to `warnings` for a takeover.
  StudyLock(const std::string& dir, bool force_unlock, std::vector<std::string>& warnings);
  ~StudyLock();
  StudyLock(const StudyLock&) = delete;
  StudyLock& operator=(const StudyLock&) = delete;

  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace seedcal
