#pragma once
// Runs the built seedcal binary (path from SEEDCAL_BINARY, set by ctest) and captures its exit code
// and combined output.
#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>

namespace seedcal::testing {

struct CliResult {
  int exit_code = -1;
  std::string output;
};

inline std::string seedcal_binary() {
  const char* b = std::getenv("SEEDCAL_BINARY");
  return b ? b : "build/seedcal";
}

inline std::string source_dir() {
  const char* s = std::getenv("SEEDCAL_SOURCE_DIR");
  return s ? s : ".";
}

// Runs a shell command line; its exit code and standard output.
inline CliResult run_shell(const std::string& cmd) {
  CliResult r;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf{};
  std::size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.output.append(buf.data(), n);
  const int status = pclose(p);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

inline CliResult run_cli(const std::string& args) { return run_shell(seedcal_binary() + " " + args + " 2>&1"); }

// A fresh scratch directory under the system temp dir.
inline std::string scratch_dir(const std::string& name) {
  const auto d = std::filesystem::temp_directory_path() / ("seedcal-test-" + name + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d.string();
}

inline std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

inline void write_text(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
}

}  // namespace seedcal::testing
