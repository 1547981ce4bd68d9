#include "calibrate/scenes/rig_checks.hpp"

#include <algorithm>
#include <cstdio>

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

void warn_if_small_rig(TomlReader& rig, const std::string& key, const std::string& what, double size_m,
                       const SeedSpec& seeds, const RigMinimum& min, const std::string& fix) {
  const double length = seed_length_m(seeds);
  if (!(length > 0.0) || size_m >= min.lengths * length) return;
  char text[240];
  std::snprintf(text, sizeof text, "is small for the seed: %s is %.4g m, %.1f seed lengths (seed length %.2f mm), under %.0f: ",
                what.c_str(), size_m, size_m / length, 1e3 * length, min.lengths);
  char to[64];
  std::snprintf(to, sizeof to, "%.4g m", min.lengths * length);
  rig.warn(key, text + std::string(min.reason) + "; " +
                    (fix.empty() ? "raise it to at least " + std::string(to) : fix + " (" + what + " at least " + to + ")") +
                    " or use a smaller seed");
}

}  // namespace seedcal
