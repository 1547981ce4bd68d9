#pragma once
// The errors the libraries above the solver report (configs, the pipeline, the store, reports):
// bad input and a run that failed. The program maps them to its exit codes (app/exit_codes.hpp:
// 2 and 1).
#include <stdexcept>
#include <string>
#include <vector>

namespace seedcal {

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
