#include "calibrate/clumps/size_distribution.hpp"

#include <algorithm>
#include <stdexcept>

namespace seedcal {

ScaleDistribution width_scale_distribution(const Variety& v, double sds, double template_width_m) {
  if (!(sds > 0.0 && sds <= 5.0)) throw std::invalid_argument("size distribution: sds must be in (0, 5]");
  if (!(v.width_mean_m > 0.0)) throw std::invalid_argument("size distribution: the variety has no mean width");
  ScaleDistribution d;
  d.mean = template_width_m > 0.0 ? v.width_mean_m / template_width_m : 1.0;
  d.sd = v.width_dist_sd_m / (template_width_m > 0.0 ? template_width_m : v.width_mean_m);
  d.lo = std::max(0.2 * d.mean, d.mean - sds * d.sd);
  d.hi = d.mean + sds * d.sd;
  return d;
}

}  // namespace seedcal
