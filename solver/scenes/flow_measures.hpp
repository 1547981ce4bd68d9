#pragma once
// The custom scene's measurements (docs/scenes/custom.md), each on plain arrays so that it can be
// checked on a hand-built case:
//   mass_in_box      kg of the bodies whose centre of mass lies in an axis-aligned box
//   PlaneCrossing    cumulative kg whose centres crossed a plane, counted from the sign change of
//                    each body's signed distance between two updates (+ along the normal, - back)
//   steady_rate      kg/s: the slope of a least-squares line through the cumulative mass against
//                    time, over the window where it lies between two fractions of its final value
//                    (the start-up and the hopper's emptying are left out; Beverloo's rate is that
//                    of the steady flow between them: Beverloo, Leniger & van de Velde 1961, Chem.
//                    Eng. Sci. 15, 260)
//   surface_heights  height of the bed's top above a horizontal line, at points along it
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

#include "solver/core/vec.hpp"
#include "solver/scenes/line_fit.hpp"

namespace seedcal {

struct BoxRegion {
  Vec3 lo_m = Vec3::Zero(), hi_m = Vec3::Zero();
  bool contains(const Vec3& p) const {
    return (p.array() >= lo_m.array()).all() && (p.array() <= hi_m.array()).all();
  }
};

double mass_in_box(const std::vector<Vec3>& centres, const std::vector<double>& masses, const BoxRegion& box);

class PlaneCrossing {
 public:
  // The plane through `point_m` with unit normal along `normal` (the direction of flow counted +).
  PlaneCrossing(const Vec3& point_m, const Vec3& normal);
  // The bodies now (id, centre, mass): a body whose side changed since it was last seen adds its
  // mass (crossed along the normal) or takes it off (crossed back). A body seen for the first time
  // only records its side; a body no longer present is forgotten. A centre on the plane counts as
  // on its back side.
  void update(const std::vector<std::uint32_t>& ids, const std::vector<Vec3>& centres,
              const std::vector<double>& masses);
  double crossed_kg() const { return crossed_kg_; }

 private:
  Vec3 point_, normal_;
  std::unordered_map<std::uint32_t, bool> ahead_;  // id -> centre on the normal's side
  double crossed_kg_ = 0.0;
};

struct SteadyRate {
  double rate_kg_s = 0.0;
  LineFit fit;
  double t_begin_s = 0.0, t_end_s = 0.0;  // the window's first and last sample
  bool ok = false;                        // at least 3 samples in the window, a line fitted
};

// `time_s` increasing, `cumulative_kg` the crossed mass at each time; the window is the samples
// whose cumulative mass lies in [fraction_lo, fraction_hi] x its last value.
SteadyRate steady_rate(const std::vector<double>& time_s, const std::vector<double>& cumulative_kg,
                       double fraction_lo, double fraction_hi);

// Height above `line_z_m` of the highest sphere surface within `probe_radius_m` (horizontally) of
// each point (x, y): a vertical probe of that radius lowered onto the bed touches a sphere of centre
// c and radius r at rho = its horizontal distance from the probe's axis when rho < r + a, at height
// c.z + sqrt(r^2 - max(0, rho - a)^2). 0 where no sphere reaches above the line.
std::vector<double> surface_heights(const std::vector<std::pair<Vec3, double>>& spheres,
                                    const std::vector<Vec3>& points, double line_z_m, double probe_radius_m);

}  // namespace seedcal
