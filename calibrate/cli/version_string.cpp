#include "calibrate/cli/version_string.hpp"

#include "calibrate/cli/version.hpp"

namespace seedcal {

std::string version_string() { return std::string(kVersion) + " (" + kGitRevision + ")"; }

}  // namespace seedcal
