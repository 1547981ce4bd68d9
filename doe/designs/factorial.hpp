#pragma once
// Two-level full and fractional factorials and the 3^k factorial (Montgomery, Design and Analysis
// of Experiments, 8th ed., ch. 6, 8 and 9).
#include <string>
#include <vector>

#include "doe/designs/design.hpp"

namespace seedcal::doe {

// 2^k in standard (Yates) order: column 1 alternates fastest, first run all -1. k in [1, 20].
Design full_factorial_2level(int k);

// 2^(k-p): the first k-p factors form a full factorial in standard order; each generator
// "D=ABC" (or "D=-ABC") defines a further factor as the product of base columns. Factors are
// lettered A, B, C, ... in order (Montgomery, sec. 8.2). Letters name columns 1..k.
Design fractional_factorial(int k, const std::vector<std::string>& generators);

// 3^k with levels -1, 0, +1, first column fastest. k in [1, 10].
Design full_factorial_3level(int k);

// Product of the given columns of a design (an interaction column).
Eigen::VectorXd interaction_column(const Eigen::MatrixXd& coded, const std::vector<int>& columns);

}  // namespace seedcal::doe
