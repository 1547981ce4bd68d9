#include "calibrate/io/atomic_file.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <unistd.h>

#include "calibrate/cli/errors.hpp"

namespace seedcal {

void write_file_atomic(const std::string& path, const std::string& content) {
  const std::filesystem::path target(path);
  if (target.has_parent_path()) std::filesystem::create_directories(target.parent_path());
  const std::string tmp = path + ".tmp." + std::to_string(::getpid());
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) throw RunFailed("cannot write " + tmp + ": " + std::strerror(errno));
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
