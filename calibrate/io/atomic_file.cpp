#include "calibrate/io/atomic_file.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <sys/stat.h>
#include <unistd.h>

#include "calibrate/cli/errors.hpp"

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
  if (::fsync(fd) != 0 || ::close(fd) != 0) {
    ::unlink(tmp.c_str());
    throw RunFailed("cannot flush " + tmp + ": " + std::strerror(errno));
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    ::unlink(tmp.c_str());
    throw RunFailed("cannot rename " + tmp + " to " + path + ": " + std::strerror(errno));
  }
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
