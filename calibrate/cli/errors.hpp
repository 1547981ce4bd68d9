#pragma once
// The CLI's error kinds and exit codes (DESIGN.md, "Interface"): 0 success, 2 bad input, 1 a run
// that failed.
#include <stdexcept>
#include <string>
#include <vector>

namespace seedcal {

inline constexpr int kExitOk = 0;
inline constexpr int kExitRunFailed = 1;
inline constexpr int kExitBadInput = 2;

// Bad input: one or more messages, each of the form
//   "FILE:LINE: KEY = VALUE: what is wrong (allowed range)".
class InputError : public std::runtime_error {
 public:
  explicit InputError(std::vector<std::string> problems);
  explicit InputError(const std::string& problem) : InputError(std::vector<std::string>{problem}) {}
  const std::vector<std::string>& problems() const { return problems_; }

 private:
  std::vector<std::string> problems_;
};

// A simulation or study that ran and failed (unstable, a guard tripped, I/O failure).
class RunFailed : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace seedcal
