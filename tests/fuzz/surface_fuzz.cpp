// libFuzzer target: the PLY and OBJ readers (solver/walls/surface_reader.hpp) on arbitrary bytes,
// each input given to both. Every malformed input must end in a SettingError naming the file;
// anything else (a crash, a sanitizer report, another exception, a non-finite vertex) is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "solver/core/errors.hpp"
#include "solver/walls/surface_reader.hpp"

namespace {

template <typename Parse>
void check(Parse parse, const std::string& bytes, const char* name) {
  try {
    for (const auto& t : parse(bytes, name, 1e-3))
      for (const auto& v : t)
        if (!v.allFinite()) __builtin_trap();  // the readers promise finite vertices
  } catch (const seedcal::SettingError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  check([](const std::string& b, const char* n, double s) { return seedcal::parse_ply(b, n, s); }, bytes, "fuzz.ply");
  check([](const std::string& b, const char* n, double s) { return seedcal::parse_obj(b, n, s); }, bytes, "fuzz.obj");
  return 0;
}
