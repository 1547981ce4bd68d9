#include "store/atomic_file.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <sys/stat.h>
#include <unistd.h>

#include "store/errors.hpp"

namespace seedcal {

void write_file_atomic(const std::string& path, const std::string& content) {
  const std::filesystem::path target(path);
  if (target.has_parent_path()) std::filesystem::create_directories(target.parent_path());
  // A unique temporary name next to the target (mkstemp: O_EXCL, so two writers of one path, in
  // one process or several, never share a temporary file); the rename is atomic within the folder.
  std::string tmp = path + ".tmp.XXXXXX";
  const int fd = ::mkstemp(tmp.data());
  if (fd < 0) throw RunFailed("cannot write " + path + ".tmp.*: " + std::strerror(errno));
  ::fchmod(fd, 0644);  // mkstemp creates 0600; the outputs are plain readable files
  std::size_t done = 0;
  while (done < content.size()) {
    const ssize_t n = ::write(fd, content.data() + done, content.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      const std::string err = std::strerror(errno);
      ::close(fd);
      ::unlink(tmp.c_str());
      throw RunFailed("cannot write " + tmp + ": " + err);
    }
    done += static_cast<std::size_t>(n);
  }
  if (::close(fd) != 0) {
    ::unlink(tmp.c_str());
    throw RunFailed("cannot close " + tmp + ": " + std::strerror(errno));
  }
  commit_file_atomic(tmp, path);
}

namespace {

void fsync_or_throw(const std::string& path, int flags, const std::string& what) {
  const int fd = ::open(path.c_str(), flags);
  if (fd < 0) throw RunFailed("cannot open " + path + " to flush " + what + ": " + std::strerror(errno));
  const int rc = ::fsync(fd);
  const int err = errno;
  ::close(fd);
  // EINVAL: a folder on a file system that cannot sync directories; the rename is still atomic.
  if (rc != 0 && !(err == EINVAL && (flags & O_DIRECTORY)))
    throw RunFailed("cannot flush " + what + " " + path + ": " + std::strerror(err));
}

}  // namespace

void commit_file_atomic(const std::string& tmp, const std::string& path) {
  try {
    fsync_or_throw(tmp, O_RDONLY, "the file");
  } catch (...) {
    ::unlink(tmp.c_str());
    throw;
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string err = std::strerror(errno);
    ::unlink(tmp.c_str());
    throw RunFailed("cannot rename " + tmp + " to " + path + ": " + err);
  }
  const std::filesystem::path dir = std::filesystem::path(path).parent_path();
  fsync_or_throw(dir.empty() ? "." : dir.string(), O_RDONLY | O_DIRECTORY, "the folder");
}

std::string find_non_finite(const nlohmann::json& j, const std::string& where) {
  if (j.is_number_float() && !std::isfinite(j.get<double>())) return where.empty() ? "/" : where;
  if (j.is_object())
    for (auto it = j.begin(); it != j.end(); ++it) {
      const std::string r = find_non_finite(it.value(), where + "/" + it.key());
      if (!r.empty()) return r;
    }
  if (j.is_array())
    for (std::size_t i = 0; i < j.size(); ++i) {
      const std::string r = find_non_finite(j[i], where + "/" + std::to_string(i));
      if (!r.empty()) return r;
    }
  return "";
}

void write_json_atomic(const std::string& path, const nlohmann::json& j) {
  const std::string bad = find_non_finite(j);
  if (!bad.empty())
    throw RunFailed("refusing to write " + path + ": the value at " + bad + " is not finite");
  write_file_atomic(path, j.dump(2) + "\n");
}

}  // namespace seedcal
