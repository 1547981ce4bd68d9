#pragma once
// Central composite designs (Box & Wilson 1951; Montgomery DAE 8th ed., sec. 11.4.2; NIST/SEMATECH
// e-Handbook sec. 5.3.3.6.1): a 2^k (or 2^(k-p)) factorial, 2k axial runs at +-alpha on each axis,
// and centre runs.
//   circumscribed (rotatable): alpha = n_F^(1/4), n_F the number of factorial runs (Montgomery
//                              eq. 11.22), axial runs outside the +-1 cube;
//   face_centered: alpha = 1;
//   inscribed: the rotatable design scaled by 1/alpha so the axial runs sit at +-1 and the
//              factorial runs at +-1/alpha.
#include <cstdint>
#include <string>
#include <vector>

#include "doe/designs/design.hpp"

namespace seedcal::doe {

enum class CcdType { circumscribed, face_centered, inscribed };

struct CentralCompositeOptions {
  int factors = 2;                      // 2 .. 10
  CcdType type = CcdType::circumscribed;
  double alpha = 0.0;                   // > 0 overrides the type's alpha (circumscribed only)
  int center_points = 5;
  std::vector<std::string> generators;  // optional 2^(k-p) factorial part, e.g. {"E=ABCD"}
  bool randomize = false;
  std::uint64_t seed = 1;
  bool IsValid(std::string* error) const;
};

// Rotatable axial distance n_F^(1/4).
double rotatable_alpha(int factorial_runs);

Design central_composite(const CentralCompositeOptions& options);

}  // namespace seedcal::doe
