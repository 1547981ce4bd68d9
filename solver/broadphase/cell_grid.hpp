#pragma once
// Uniform cell list over the spheres' bounding box: spheres sorted by cell with a counting sort,
// so the spheres of one cell are contiguous. Cell edge >= the largest sphere diameter plus the
// Verlet skin, so every pair that can come within the skin lies in adjacent cells.
#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "solver/core/vec.hpp"

namespace seedcal {

class CellGrid {
 public:
  // Bins the given centres. `min_cell_m` is the smallest allowed cell edge. The number of cells is
  // kept below a few per sphere by enlarging cells when the spheres are spread out, so a particle
  // that flies far away cannot blow up memory.
  void build(const std::vector<Vec3>& centres, double min_cell_m);

  std::array<int, 3> dims() const { return dims_; }
  std::array<int, 3> cell_of(const Vec3& p) const;
  int linear(int x, int y, int z) const { return (z * dims_[1] + y) * dims_[0] + x; }
  // Spheres in cell c: sorted_[start_[c] .. start_[c+1]).
  const std::vector<std::uint32_t>& sorted() const { return sorted_; }
  const std::vector<std::uint32_t>& start() const { return start_; }
  const std::vector<int>& cell_index() const { return cell_index_; }
  // Calls f(index) for every entry binned in the cell of p and in its neighbours inside the grid
  // (up to 27 cells, z outermost, then y, then x).
  template <class F>
  void for_each_near(const Vec3& p, F&& f) const {
    const std::array<int, 3> c = cell_of(p);
    for (int z = std::max(0, c[2] - 1); z <= std::min(dims_[2] - 1, c[2] + 1); ++z)
      for (int y = std::max(0, c[1] - 1); y <= std::min(dims_[1] - 1, c[1] + 1); ++y)
        for (int x = std::max(0, c[0] - 1); x <= std::min(dims_[0] - 1, c[0] + 1); ++x) {
          const auto cell = static_cast<std::size_t>(linear(x, y, z));
          for (std::uint32_t k = start_[cell]; k < start_[cell + 1]; ++k) f(sorted_[k]);
        }
  }

 private:
  Vec3 lo_ = Vec3::Zero();
  double inv_edge_ = 1.0;
  std::array<int, 3> dims_{1, 1, 1};
  std::vector<int> cell_index_;        // cell of each sphere
  std::vector<std::uint32_t> sorted_;  // sphere ids ordered by cell
  std::vector<std::uint32_t> start_;   // size cells + 1
};

}  // namespace seedcal
