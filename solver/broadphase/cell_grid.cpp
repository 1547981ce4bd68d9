#include "solver/broadphase/cell_grid.hpp"

#include <algorithm>
#include <cmath>

namespace seedcal {

void CellGrid::build(const std::vector<Vec3>& centres, double min_cell_m) {
  const std::size_t n = centres.size();
  Vec3 lo = Vec3::Constant(0.0), hi = Vec3::Constant(0.0);
  if (n > 0) {
    lo = centres[0];
    hi = centres[0];
    for (const Vec3& p : centres) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  }
  double edge = std::max(min_cell_m, 1e-12);
  const Vec3 span = (hi - lo).cwiseMax(Vec3::Constant(edge));
  // At most ~4 cells per sphere (and at least 1): enough resolution, bounded memory.
  const double max_cells = std::max(64.0, 4.0 * static_cast<double>(n));
  while ((std::floor(span.x() / edge) + 1) * (std::floor(span.y() / edge) + 1) *
             (std::floor(span.z() / edge) + 1) > max_cells)
    edge *= 1.26;  // ~2^(1/3): halves the cell count per iteration
  lo_ = lo;
  inv_edge_ = 1.0 / edge;
  for (int d = 0; d < 3; ++d) dims_[d] = static_cast<int>(std::floor(span[d] / edge)) + 1;

  const std::size_t cells = static_cast<std::size_t>(dims_[0]) * dims_[1] * dims_[2];
  cell_index_.resize(n);
  start_.assign(cells + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = cell_of(centres[i]);
    cell_index_[i] = linear(c[0], c[1], c[2]);
    ++start_[static_cast<std::size_t>(cell_index_[i]) + 1];
  }
  for (std::size_t c = 0; c < cells; ++c) start_[c + 1] += start_[c];
  sorted_.resize(n);
  std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
  for (std::size_t i = 0; i < n; ++i) sorted_[fill[static_cast<std::size_t>(cell_index_[i])]++] =
      static_cast<std::uint32_t>(i);
}

std::array<int, 3> CellGrid::cell_of(const Vec3& p) const {
  std::array<int, 3> c{};
  for (int d = 0; d < 3; ++d) {
    const int v = static_cast<int>(std::floor((p[d] - lo_[d]) * inv_edge_));
    c[d] = std::clamp(v, 0, dims_[d] - 1);
  }
  return c;
}

}  // namespace seedcal
