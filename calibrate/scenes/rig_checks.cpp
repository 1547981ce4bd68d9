#include "calibrate/scenes/rig_checks.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>

namespace seedcal {

double seed_length_m(const SeedSpec& seeds) {
  double longest = 0.0;
  for (int k = 0; k < 3; ++k) {
    double lo = 0.0, hi = 0.0;
    bool first = true;
    for (const SphereDef& s : seeds.body.spheres) {
      const double a = s.offset_m[k] - s.radius_m, b = s.offset_m[k] + s.radius_m;
      lo = first ? a : std::min(lo, a);
      hi = first ? b : std::max(hi, b);
      first = false;
    }
    longest = std::max(longest, hi - lo);
  }
  return longest * seeds.scale.mean;
}

namespace {

// `value` printed with the fewest digits (from `digits` on, up to nine) that still show it on the
// right side of `bound`: a size a hair under its minimum must not read as the minimum itself
// ("2.0 seed lengths, under 2").
std::string shown_against(double value, double bound, bool below, const char* format, int digits) {
  char out[64];
  for (int d = digits; d <= 9; ++d) {
    std::snprintf(out, sizeof out, format, d, value);
    const double read = std::strtod(out, nullptr);
    if (below ? read < bound : read > bound) break;
  }
  return out;
}

}  // namespace

void warn_if_small_rig(TomlReader& rig, const std::string& key, const std::string& what, double size_m,
                       const SeedSpec& seeds, const RigMinimum& min, const std::string& fix) {
  const double length = seed_length_m(seeds);
  if (!(length > 0.0) || size_m >= min.lengths * length) return;
  const std::string lengths = shown_against(size_m / length, min.lengths, true, "%.*f", 1);
  const std::string to = shown_against(min.lengths * length, size_m, false, "%.*g", 4) + " m";
  char text[240];
  std::snprintf(text, sizeof text, "is small for the seed: %s is %.4g m, %s seed lengths (seed length %.2f mm), under %.0f: ",
                what.c_str(), size_m, lengths.c_str(), 1e3 * length, min.lengths);
  rig.warn(key, text + std::string(min.reason) + "; " +
                    (fix.empty() ? "raise it to at least " + to : fix + " (" + what + " at least " + to + ")") +
                    " or use a smaller seed");
}

}  // namespace seedcal
