#include "reports/gnuplot_svg.hpp"

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <signal.h>
#include <sstream>
#include <stdexcept>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

namespace seedcal::reports {
namespace {

namespace fs = std::filesystem;

std::string read_all(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_all(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + p.string());
}

// The executable to run: $SEEDCAL_GNUPLOT, or the first `gnuplot` on PATH.
std::string gnuplot_path() {
  if (const char* e = std::getenv("SEEDCAL_GNUPLOT"); e && *e) return e;
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "/usr/bin:/bin";
  std::size_t start = 0;
  while (start <= dirs.size()) {
    const std::size_t end = std::min(dirs.find(':', start), dirs.size());
    const fs::path candidate = fs::path(dirs.substr(start, end - start)) / "gnuplot";
    if (::access(candidate.c_str(), X_OK) == 0) return candidate.string();
    start = end + 1;
  }
  throw std::runtime_error("gnuplot is not installed (Debian: apt-get install gnuplot-nox); plots are left out");
}

// A temporary directory removed when it goes out of scope.
struct TempDir {
  fs::path path;
  TempDir() {
    std::string templ = (fs::temp_directory_path() / "seedcal-gnuplot-XXXXXX").string();
    if (!::mkdtemp(templ.data())) throw std::runtime_error("cannot create a temporary directory: " + std::string(std::strerror(errno)));
    path = templ;
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
};

}  // namespace

void GnuplotPlot::add_data(const std::string& name, const std::vector<std::vector<double>>& rows) {
  std::string text;
  for (const auto& r : rows) {
    bool finite = true;
    for (double v : r) finite = finite && std::isfinite(v);
    if (!finite) continue;
    for (std::size_t i = 0; i < r.size(); ++i) text += std::string(i ? " " : "") + gp_number(r[i]);
    text += "\n";
  }
  data.emplace_back(name, text);
}

std::string gp_quote(std::string_view text) {
  std::string out = "'";
  for (char c : text) {
    if (c == '\'') out += "''";
    else if (c == '\n' || c == '\r') out += ' ';
    else out += c;
  }
  return out + "'";
}

std::string gp_data_string(std::string_view text) {
  std::string out = "\"";
  for (char c : text) out += c == '"' ? '\'' : (c == '\n' || c == '\r') ? ' ' : c;
  return out + "\"";
}

std::string gp_number(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string render_gnuplot_svg(const GnuplotPlot& plot) {
  const std::string exe = gnuplot_path();
  TempDir dir;
  for (const auto& [name, content] : plot.data) write_all(dir.path / name, content);
  const std::string script = std::string("set terminal svg size ") + std::to_string(plot.width) + "," + std::to_string(plot.height) +
                             " noenhanced font 'sans,11' background '#ffffff'\nset encoding utf8\nset output 'plot.svg'\n"
                             "set format x '%.4g'\nset format y '%.4g'\nset format cb '%.4g'\n" +
                             plot.script + "\nunset output\n";
  write_all(dir.path / "plot.gp", script);

  // Everything the child needs is prepared before fork: it only calls async-signal-safe functions.
  const std::string dir_s = dir.path.string(), err_s = (dir.path / "gnuplot.err").string();
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error("cannot start gnuplot: " + std::string(std::strerror(errno)));
  if (pid == 0) {
    const int devnull = ::open("/dev/null", O_RDWR);
    const int err = ::open(err_s.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (devnull < 0 || err < 0 || ::chdir(dir_s.c_str()) != 0) ::_exit(127);
    ::dup2(devnull, STDIN_FILENO);
    ::dup2(err, STDOUT_FILENO);
    ::dup2(err, STDERR_FILENO);
    ::execl(exe.c_str(), "gnuplot", "-d", "plot.gp", static_cast<char*>(nullptr));
    ::_exit(127);
  }
  int status = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  for (;;) {
    const pid_t r = ::waitpid(pid, &status, WNOHANG);
    if (r == pid) break;
    if (r < 0 && errno != EINTR) throw std::runtime_error("waiting for gnuplot: " + std::string(std::strerror(errno)));
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      throw std::runtime_error("gnuplot ran longer than 60 s and was stopped");
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  const std::string messages = read_all(dir.path / "gnuplot.err");
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error("gnuplot (" + exe + ") failed" +
                             (WIFEXITED(status) && WEXITSTATUS(status) == 127 ? std::string(" to start") : std::string()) +
                             (messages.empty() ? std::string() : ": " + messages));
  std::string svg = read_all(dir.path / "plot.svg");
  if (svg.find("<svg") == std::string::npos) throw std::runtime_error("gnuplot wrote no SVG" + (messages.empty() ? std::string() : ": " + messages));
  return svg;
}

}  // namespace seedcal::reports
