#pragma once
// Numbers doe/ shares.
#include <limits>

namespace seedcal::doe {

// "Not available": a statistic that is undefined (no residual degrees of freedom, a zero
// variance), reported as NaN and written as null or "-".
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace seedcal::doe
