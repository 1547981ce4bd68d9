#pragma once
// Errors and option validation shared by every doe/ routine (STYLE.md, after Ceres' Options::IsValid):
// each problem names the option, its value and the constraint it violates, e.g.
//   "PlackettBurmanOptions.runs = 10: must be one of 8, 12, 16, 20, 24".
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace seedcal::doe {

// Invalid options or data handed to a doe routine. The CLI turns it into a bad-input error.
class DoeError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// Collects every problem of one options struct, so the user sees all of them at once.
class Problems {
 public:
  template <class T>
  void require(bool ok, const std::string& option, const T& value, const std::string& constraint) {
    if (ok) return;
    std::ostringstream s;
    s << option << " = " << value << ": " << constraint;
    list_.push_back(s.str());
  }
  void add(const std::string& problem) { list_.push_back(problem); }
  bool empty() const { return list_.empty(); }
  // All problems, one a line.
  std::string text() const {
    std::string t;
    for (const auto& p : list_) {
      if (!t.empty()) t.push_back('\n');
      t.append(p);
    }
    return t;
  }
  // Ceres-style: true when valid, else false with the problems in *error (when error is given).
  bool report(std::string* error) const {
    if (error) *error = text();
    return empty();
  }
  void throw_if_any() const {
    if (!empty()) throw DoeError(text());
  }

 private:
  std::vector<std::string> list_;
};

// Throws DoeError with the problems of opts (any type with IsValid(std::string*)).
template <class Options>
void validate_or_throw(const Options& opts) {
  std::string error;
  if (!opts.IsValid(&error)) throw DoeError(error);
}

}  // namespace seedcal::doe
