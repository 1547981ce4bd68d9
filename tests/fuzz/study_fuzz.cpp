// libFuzzer target: the study-file loader (TOML parser, typed reader, every range check). A bad
// file must end in an InputError that names it; anything else is a finding.
#include "calibrate/pipeline/study_config.hpp"
#include "store/errors.hpp"
#include "tests/fuzz/file_fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = seedcal::fuzz::write_input(data, size, "study.toml");
  try {
    const seedcal::StudyConfig s = seedcal::read_study(path);
    if (s.targets.empty() || s.parameters.empty()) __builtin_trap();  // accepted means complete
  } catch (const seedcal::InputError& e) {
    if (std::string(e.what()).find(path) == std::string::npos) __builtin_trap();  // names the file
  }
  return 0;
}
