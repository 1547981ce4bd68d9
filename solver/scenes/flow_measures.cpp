#include "solver/scenes/flow_measures.hpp"

#include <algorithm>
#include <cmath>

namespace seedcal {

double mass_in_box(const std::vector<Vec3>& centres, const std::vector<double>& masses, const BoxRegion& box) {
  double m = 0.0;
  for (std::size_t i = 0; i < centres.size(); ++i)
    if (box.contains(centres[i])) m += masses[i];
  return m;
}

PlaneCrossing::PlaneCrossing(const Vec3& point_m, const Vec3& normal)
    : point_(point_m), normal_(normal.normalized()) {}

void PlaneCrossing::update(const std::vector<std::uint32_t>& ids, const std::vector<Vec3>& centres,
                           const std::vector<double>& masses) {
  std::unordered_map<std::uint32_t, bool> now;
  now.reserve(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i) {
    const bool ahead = (centres[i] - point_).dot(normal_) > 0.0;
    now.emplace(ids[i], ahead);
    const auto was = ahead_.find(ids[i]);
    if (was == ahead_.end() || was->second == ahead) continue;
    crossed_kg_ += ahead ? masses[i] : -masses[i];
  }
  ahead_ = std::move(now);
}

SteadyRate steady_rate(const std::vector<double>& time_s, const std::vector<double>& cumulative_kg,
                       double fraction_lo, double fraction_hi) {
  SteadyRate r;
  if (cumulative_kg.empty()) return r;
  const double last = cumulative_kg.back();
  std::vector<double> t, m;
  for (std::size_t i = 0; i < time_s.size(); ++i)
    if (cumulative_kg[i] >= fraction_lo * last && cumulative_kg[i] <= fraction_hi * last) {
      t.push_back(time_s[i]);
      m.push_back(cumulative_kg[i]);
    }
  r.fit = fit_line(t, m);
  if (!r.fit.ok || !(last > 0.0)) return r;
  r.ok = true;
  r.rate_kg_s = r.fit.slope;
  r.t_begin_s = t.front();
  r.t_end_s = t.back();
  return r;
}

std::vector<double> surface_heights(const std::vector<std::pair<Vec3, double>>& spheres,
                                    const std::vector<Vec3>& points, double line_z_m, double probe_radius_m) {
  std::vector<double> h(points.size(), 0.0);
  for (std::size_t k = 0; k < points.size(); ++k) {
    double top = line_z_m;
    for (const auto& [c, r] : spheres) {
      const double rho = std::hypot(c.x() - points[k].x(), c.y() - points[k].y());
      if (rho >= r + probe_radius_m) continue;
      const double off = std::max(0.0, rho - probe_radius_m);
      top = std::max(top, c.z() + std::sqrt(r * r - off * off));
    }
    h[k] = top - line_z_m;
  }
  return h;
}

}  // namespace seedcal
