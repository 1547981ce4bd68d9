#include "solver/scenes/line_fit.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>

namespace seedcal {

LineFit fit_line(const std::vector<double>& x, const std::vector<double>& z) {
  LineFit f;
  f.points = x.size();
  if (x.size() < 3) return f;
  Eigen::MatrixXd A(x.size(), 2);
  Eigen::VectorXd b(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    A(static_cast<Eigen::Index>(i), 0) = 1.0;
    A(static_cast<Eigen::Index>(i), 1) = x[i];
    b(static_cast<Eigen::Index>(i)) = z[i];
  }
  const auto qr = A.colPivHouseholderQr();
  if (qr.rank() < 2) return f;
  const Eigen::Vector2d c = qr.solve(b);
  f.intercept = c(0);
  f.slope = c(1);
  const double mean = b.mean();
  const double ss_tot = (b.array() - mean).square().sum();
  const double ss_res = (A * c - b).squaredNorm();
  f.r2 = ss_tot > 0.0 ? 1.0 - ss_res / ss_tot : 1.0;
  f.ok = true;
  return f;
}

std::vector<std::pair<double, double>> upper_profile(const std::vector<std::pair<double, double>>& x_top,
                                                     double bin) {
  std::map<long, double> top;
  for (const auto& [x, z] : x_top) {
    const long k = static_cast<long>(std::floor(x / bin));
    auto it = top.find(k);
    if (it == top.end()) top[k] = z;
    else it->second = std::max(it->second, z);
  }
  std::vector<std::pair<double, double>> out;
  for (const auto& [k, z] : top) out.push_back({(static_cast<double>(k) + 0.5) * bin, z});
  return out;
}

}  // namespace seedcal
