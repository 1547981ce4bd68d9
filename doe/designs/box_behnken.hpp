#pragma once
// Box-Behnken designs for 3 to 7 factors (Box & Behnken, Technometrics 2 (1960) 455-475): 2^2 or
// 2^3 factorials on blocks of factors, the others at 0, plus centre runs.
//   k = 3, 4, 5: a 2^2 factorial on every pair of factors (12, 24, 40 runs);
//   k = 6: a 2^3 factorial on the 6 blocks {1,2,4} {2,3,5} {3,4,6} {1,4,5} {2,5,6} {1,3,6} (48 runs);
//   k = 7: a 2^3 factorial on the 7 blocks of the Fano plane {4,5,6} {1,6,7} {2,5,7} {1,2,4}
//          {3,4,7} {1,3,5} {2,3,6} (56 runs), as in Box & Behnken's tables.
// Default centre runs 3, 3, 6, 6, 6 (total 15, 27, 46, 54, 62 runs: NIST/SEMATECH e-Handbook,
// sec. 5.3.3.6.2, Table of Box-Behnken designs).
#include <cstdint>
#include <string>

#include "doe/designs/design.hpp"

namespace seedcal::doe {

struct BoxBehnkenOptions {
  int factors = 3;          // 3 .. 7
  int center_points = -1;   // -1: the published default for `factors`
  bool randomize = false;
  std::uint64_t seed = 1;
  bool IsValid(std::string* error) const;
};

int box_behnken_default_centers(int factors);
Design box_behnken(const BoxBehnkenOptions& options);

}  // namespace seedcal::doe
