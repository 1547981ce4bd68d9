#pragma once
// The contact models a run can choose (contact_model.hpp holds the options around them). No
// includes: the vector kernels (sim/pair_batch_avx2.cpp, sim/pair_batch_avx512.cpp) are compiled
// per instantiation of these kinds and must not include library headers.

namespace seedcal {

enum class NormalModel { hertz_mindlin, hmnr };
enum class RollingModel { none, cdt, epsd };

}  // namespace seedcal
