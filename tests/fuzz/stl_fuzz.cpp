// libFuzzer target: the STL reader (binary and ASCII) on arbitrary bytes. Every malformed input
// must end in a SettingError naming the file; anything else (a crash, a sanitizer report, another
// exception) is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "solver/core/errors.hpp"
#include "solver/walls/stl_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  try {
    const auto triangles = seedcal::parse_stl(bytes, "fuzz.stl", 1e-3);
    for (const auto& t : triangles)
      for (const auto& v : t)
        if (!v.allFinite()) __builtin_trap();  // the reader promises finite vertices
  } catch (const seedcal::SettingError&) {
  }
  return 0;
}
