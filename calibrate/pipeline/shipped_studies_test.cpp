// Every study shipped in data/studies/ reads and validates, and every scene it will run passes the
// check `seedcal calibrate` makes before its first run (pipeline/scene_check.hpp: each target and
// verification test under each clump model, the parameters at their nominal values and limits).
// A misspelt override, clump path or range in a shipped file fails here, not hours into a study.
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "calibrate/pipeline/scene_check.hpp"
#include "store/errors.hpp"
#include "tests/support/cli.hpp"

namespace seedcal {
namespace {

TEST(ShippedStudies, EverySceneValidatesUnderEveryModel) {
  const std::filesystem::path dir = std::filesystem::path(testing::source_dir()) / "data" / "studies";
  int studies = 0, scenes = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".toml") continue;
    const std::string file = entry.path().string();
    SCOPED_TRACE(file);
    StudyConfig s;
    ASSERT_NO_THROW(s = read_study(file)) << file;
    ++studies;
    try {
      check_study_scenes(s);
    } catch (const InputError& e) {
      for (const std::string& m : e.problems()) ADD_FAILURE() << m;
    }
    scenes += s.scene_count() * static_cast<int>(s.models.size());
  }
  EXPECT_GE(studies, 8);
  EXPECT_GE(scenes, 8);
}

}  // namespace
}  // namespace seedcal
