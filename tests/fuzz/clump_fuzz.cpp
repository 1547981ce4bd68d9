// libFuzzer target: the clump-file reader (TOML clump files written by `seedcal clump build`).
// A bad file must end in an InputError; an accepted one has finite spheres with positive radii.
#include <cmath>

#include "calibrate/clumps/clump_file.hpp"
#include "store/errors.hpp"
#include "tests/fuzz/file_fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = seedcal::fuzz::write_input(data, size, "clump.toml");
  try {
    const seedcal::ClumpModel m = seedcal::read_clump_file(path);
    for (const auto& s : m.spheres)
      if (!std::isfinite(s.radius_m) || !(s.radius_m > 0.0) || !s.centre_m.allFinite()) __builtin_trap();
  } catch (const seedcal::InputError&) {
  }
  return 0;
}
