#pragma once
// The version every output records in its provenance block: "0.1.0 (git revision)".
#include <string>

namespace seedcal {

std::string version_string();

}  // namespace seedcal
