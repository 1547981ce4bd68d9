#include "store/errors.hpp"

namespace seedcal {

InputError::InputError(std::vector<std::string> problems)
    : std::runtime_error([&] {
        std::string s;
        for (std::size_t i = 0; i < problems.size(); ++i) s += (i ? "\n" : "") + problems[i];
        return s;
      }()),
      problems_(std::move(problems)) {}

}  // namespace seedcal
