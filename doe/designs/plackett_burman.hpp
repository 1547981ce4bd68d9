#pragma once
// Plackett-Burman screening designs (Plackett & Burman, Biometrika 33 (1946) 305-325) for
// 8, 12, 16, 20 and 24 runs. 12, 20 and 24 runs are cyclic: the first row is the published
// generator, each next row is the previous shifted one place right (the last sign wraps to the
// front), and a final row of all minus signs is appended (Montgomery, DAE 8th ed., sec. 8.7.2,
// Table 8.23). 8 and 16 runs are the 2^(7-4) and 2^(15-11) resolution III fractional factorials,
// i.e. all columns of the 2^3 and 2^4 factorials with their interaction columns.
#include <cstdint>
#include <string>
#include <vector>

#include "doe/designs/design.hpp"

namespace seedcal::doe {

struct PlackettBurmanOptions {
  int runs = 12;            // 8, 12, 16, 20 or 24
  int factors = 11;         // 1 .. runs - 1; the remaining runs - 1 - factors columns are dummies
  int center_points = 0;    // centre runs appended (a curvature check and pure error)
  bool randomize = false;   // randomised run order
  std::uint64_t seed = 1;
  bool IsValid(std::string* error) const;
};

// The published first row for runs = 12, 20, 24 (+1 / -1, runs - 1 entries).
std::vector<int> plackett_burman_generator(int runs);

// Columns: `factors` factor columns x1.., then dummy1.. dummy columns.
Design plackett_burman(const PlackettBurmanOptions& options);

}  // namespace seedcal::doe
