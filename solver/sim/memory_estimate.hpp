#pragma once
// How much memory a simulation of a given size needs, counted from the data structures it
// allocates, and a refusal before anything is allocated when the machine does not have it
// (a scene asking for 1e8 spheres is refused with the estimate, not killed by the kernel halfway
// through the pour).
#include <cstddef>
#include <string>

namespace seedcal {

struct MemoryEstimate {
  std::size_t bodies = 0;
  std::size_t spheres = 0;
  double neighbour_pairs = 0.0;  // expected sphere-sphere pairs in the Verlet list
  double body_bytes = 0.0;       // all per-body arrays
  double sphere_bytes = 0.0;     // all per-sphere arrays, the cell grid and the sort scratch
  double pair_bytes = 0.0;       // neighbour and wall-contact lists with their history
  double total_bytes() const { return body_bytes + sphere_bytes + pair_bytes; }
  // "1.2e+08 bodies, 1.1e+09 spheres: 7.3e+11 bytes (bodies 3.1e+11, spheres ..., pairs ...)"
  std::string describe() const;
};

// Expected neighbour-list pairs per sphere (each pair counted once). Measured: 3.1 in a settled
// bed of 1,500 equal spheres (skin 0.2 r), 1.4 in a bed of 200 nine-sphere clumps; 4 covers both.
inline constexpr double kPairsPerSphere = 4.0;

// Estimate for `bodies` bodies holding `spheres` spheres in total, run on `threads` OpenMP threads;
// `rolling_history` when EPSD keeps a rolling spring per contact.
MemoryEstimate estimate_memory(std::size_t bodies, std::size_t spheres, int threads,
                               bool rolling_history);

// Memory this process may still use, bytes: MemAvailable from /proc/meminfo, lowered to the
// cgroup v2 limit (memory.max - memory.current) when one is set. Infinity when neither can be
// read (then nothing is refused).
double available_memory_bytes();

// Throws SettingError(key, ...) when the estimate exceeds `available_bytes`; the message gives the
// estimate, what is available and the size asked for (`what`, e.g. "container_m = [2, 2, 2] m
// holds about 1.6e+07 seeds").
void check_memory(const MemoryEstimate& estimate, double available_bytes, const std::string& key,
                  const std::string& what);

}  // namespace seedcal
