#pragma once
// Maximin Latin hypercube (McKay, Beckman & Conover, Technometrics 21 (1979) 239-245; maximin
// criterion of Johnson, Moore & Ylvisaker, J. Stat. Plan. Inference 26 (1990) 131-148): n runs,
// each factor's range cut into n equal strata with exactly one run in each. Among `candidates`
// random hypercubes the one with the largest minimum pairwise distance is kept, then improved by
// swapping two runs' levels in one column whenever that raises the minimum distance (the
// elementary perturbation of Morris & Mitchell, J. Stat. Plan. Inference 43 (1995) 381-402).
// Coded range [-1, 1].
#include <cstdint>
#include <string>

#include "doe/designs/design.hpp"

namespace seedcal::doe {

struct LatinHypercubeOptions {
  int runs = 10;           // >= 2
  int factors = 2;         // >= 1
  int candidates = 20;     // random starts
  int swap_iterations = 2000;
  bool centered = false;   // true: each run at its stratum's midpoint; false: uniform inside it
  std::uint64_t seed = 1;
  bool IsValid(std::string* error) const;
};

Design latin_hypercube(const LatinHypercubeOptions& options);

// Smallest Euclidean distance between two rows.
double min_pairwise_distance(const Eigen::MatrixXd& points);

}  // namespace seedcal::doe
