#pragma once
// Output files are written to a temporary file in the same directory and renamed over the target,
// so a crash or kill never leaves a half-written metrics file or report.
#include <string>

#include <nlohmann/json.hpp>

namespace seedcal {

// Writes `content` to a temporary file beside `path`, then commit_file_atomic.
void write_file_atomic(const std::string& path, const std::string& content);

// Makes a finished temporary file `tmp` (in the target's directory) the file `path`: fsync the
// file, rename it over the target (atomic within a folder, POSIX rename(2)), fsync the folder so
// that the rename itself survives a power cut (without it a crash may bring back the old file or
// none). Every writer of seedcal's outputs ends here; throws RunFailed (the temporary removed).
void commit_file_atomic(const std::string& tmp, const std::string& path);

// JSON with every non-finite number refused: a NaN or Inf must never reach an output file.
// Throws RunFailed naming the offending key.
void write_json_atomic(const std::string& path, const nlohmann::json& j);

// Returns the first JSON pointer to a non-finite number, or "" when there is none.
std::string find_non_finite(const nlohmann::json& j, const std::string& where = "");

}  // namespace seedcal
