#pragma once
// Errors the solver reports about a setting it cannot honour. The solver has no I/O policy: the
// caller (the CLI) adds the file name and maps this to exit code 2.
#include <stdexcept>
#include <string>

namespace seedcal {

class SettingError : public std::runtime_error {
 public:
  SettingError(std::string key, const std::string& message)
      : std::runtime_error(key + ": " + message), key_(std::move(key)) {}
  const std::string& key() const { return key_; }

 private:
  std::string key_;
};

}  // namespace seedcal
