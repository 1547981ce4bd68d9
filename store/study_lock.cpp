#include "store/study_lock.hpp"

#include <cerrno>
#include <csignal>
#include <cstring>
#include <ctime>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "store/errors.hpp"

namespace seedcal {
namespace {

std::string this_host() {
  char h[256] = {};
  if (::gethostname(h, sizeof h - 1) != 0) return "unknown-host";
  return h;
}

std::string utc_now_text() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  ::gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

// Creates the lock file; false when it exists.
bool try_create(const std::string& path, const std::string& text) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
  if (fd < 0) {
    if (errno == EEXIST) return false;
    throw RunFailed("cannot create the study lock " + path + ": " + std::strerror(errno));
  }
  const ssize_t n = ::write(fd, text.data(), text.size());
  const bool ok = n == static_cast<ssize_t>(text.size()) && ::fsync(fd) == 0;
  ::close(fd);
  if (!ok) {
    ::unlink(path.c_str());
    throw RunFailed("cannot write the study lock " + path);
  }
  return true;
}

}  // namespace

StudyLock::StudyLock(const std::string& dir, bool force_unlock, std::vector<std::string>& warnings)
    : path_((std::filesystem::path(dir) / "calibrate.lock").string()) {
  std::filesystem::create_directories(dir);
  const std::string host = this_host();
  const nlohmann::json mine = {{"host", host}, {"pid", static_cast<long>(::getpid())}, {"started_utc", utc_now_text()}};
  for (int attempt = 0; attempt < 3; ++attempt) {
    if (try_create(path_, mine.dump() + "\n")) return;
    // Held: by whom?
    nlohmann::json owner;
    {
      std::ifstream in(path_);
      std::stringstream s;
      s << in.rdbuf();
      owner = nlohmann::json::parse(s.str(), nullptr, false);
    }
    const std::string o_host = owner.is_object() ? owner.value("host", std::string("?")) : std::string("?");
    const long o_pid = owner.is_object() ? owner.value("pid", -1L) : -1L;
    const std::string since = owner.is_object() ? owner.value("started_utc", std::string("?")) : std::string("?");
    const std::string who = "host " + o_host + ", pid " + std::to_string(o_pid) + ", since " + since;
    const bool same_host = o_host == host;
    const bool gone = same_host && o_pid > 0 && ::kill(static_cast<pid_t>(o_pid), 0) != 0 && errno == ESRCH;
    if (gone || force_unlock || !owner.is_object()) {
      warnings.push_back("took over the study lock " + path_ + " (" + who + "): " +
                         (gone ? "that process is gone" : !owner.is_object() ? "the lock file was unreadable"
                                                                               : "--force-unlock"));
      ::unlink(path_.c_str());
      continue;  // another process may take it first: try again
    }
    if (same_host)
      throw InputError(dir + ": another seedcal calibrate is running on this study directory (" + who +
                       "); wait for it to finish or stop it, then --resume");
    throw InputError(dir + ": the study directory is locked by a seedcal calibrate on another machine (" + who +
                     "), which cannot be checked from here; once that run is known to be gone, pass "
                     "--force-unlock to take the lock over");
  }
  throw RunFailed("cannot take the study lock " + path_ + ": other processes keep taking it");
}

StudyLock::~StudyLock() { ::unlink(path_.c_str()); }

}  // namespace seedcal
