#pragma once
// The exit codes of `seedcal` (DESIGN.md, "Interface"): 0 success, 2 bad input (InputError), 1 a
// run that failed (RunFailed, store/errors.hpp).
namespace seedcal {

inline constexpr int kExitOk = 0;
inline constexpr int kExitRunFailed = 1;
inline constexpr int kExitBadInput = 2;

}  // namespace seedcal
