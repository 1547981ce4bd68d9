#include "store/version.hpp"

#include "store/version_info.hpp"

namespace seedcal {

std::string version_string() { return std::string(kVersion) + " (" + kGitRevision + ")"; }

}  // namespace seedcal
