// Rig-to-seed checks (rig_checks.hpp): the seed length of a clump, a warning naming the key for a
// seed too large for each shipped rig, and none for the shipped scenes with their own seeds.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "calibrate/scenes/rig_checks.hpp"
#include "calibrate/scenes/scene_file.hpp"

namespace seedcal {
namespace {

TEST(RigChecks, SeedLengthIsTheLongestExtentTimesTheMeanScale) {
  SeedSpec s;
  s.body.spheres = {{Vec3(-0.002, 0.0, 0.0), 0.001}, {Vec3(0.002, 0.0, 0.0), 0.001}, {Vec3(0.0, 0.0, 0.0015), 0.001}};
  // x: -3 .. 3 mm (6 mm); y: 2 mm; z: -1 .. 2.5 mm (3.5 mm).
  EXPECT_NEAR(seed_length_m(s), 0.006, 1e-15);
  s.scale.mean = 1.5;
  EXPECT_NEAR(seed_length_m(s), 0.009, 1e-15);
}

std::vector<std::string> rig_warnings(const std::string& scene, std::vector<std::string> sets) {
  std::vector<std::string> out;
  for (const std::string& w : check_scene(load_scene_file("data/scenes/jinong1/" + scene + ".toml", sets)))
    if (w.find("is small for the seed") != std::string::npos) out.push_back(w);
  return out;
}

bool names(const std::vector<std::string>& warnings, const std::string& key) {
  for (const std::string& w : warnings)
    if (w.find(key + " is small for the seed") != std::string::npos) return true;
  return false;
}

// A user's 15 mm seed (one sphere) in the Jinong 1 rigs: 4.1 lengths across the 61.8 mm shear box
// (under 6), 1.3 lengths of sample (under 2), a 60 mm bulk container (4.0, under 5; the shipped
// quick container, 80 mm, is 5.3) and a drum bed 33.5 mm deep (2.2, under 3); the 80 mm piling
// tube is 5.3 lengths (not under 5).
TEST(RigChecks, ASeedTooLargeForTheRigIsNamedWithTheKeyToChange) {
  const std::string clump = (std::filesystem::temp_directory_path() / "seedcal-rig-check-15mm.txt").string();
  std::ofstream(clump) << "0.0 0.0 0.0 0.0075\n";
  const std::vector<std::string> big = {"fidelity=quick", "particle.clump_file=" + clump, "particle.scale_sd=0"};
  const auto shear = rig_warnings("direct_shear", big);
  EXPECT_TRUE(names(shear, "direct_shear.quick.diameter_m")) << ::testing::PrintToString(shear);
  EXPECT_TRUE(names(shear, "direct_shear.quick.sample_height_m")) << ::testing::PrintToString(shear);
  ASSERT_FALSE(shear.empty());
  EXPECT_NE(shear[0].find("4.1 seed lengths"), std::string::npos) << shear[0];
  EXPECT_NE(shear[0].find("ASTM D3080"), std::string::npos) << shear[0];
  EXPECT_NE(shear[0].find("raise it to at least 0.09 m"), std::string::npos) << shear[0];
  const std::vector<std::string> small_box = {"fidelity=quick", "particle.clump_file=" + clump, "particle.scale_sd=0",
                                              "bulk_density.quick.container_m=[0.06, 0.06, 0.06]"};
  EXPECT_TRUE(names(rig_warnings("bulk_density", small_box), "bulk_density.quick.container_m"));
  EXPECT_TRUE(rig_warnings("bulk_density", big).empty());
  EXPECT_TRUE(names(rig_warnings("drum", big), "drum.quick.filling_rate"));
  EXPECT_TRUE(rig_warnings("piling", big).empty());
  std::filesystem::remove(clump);
}

// A one-sphere seed a hair longer than half the quick sample's height: the warning shows the
// shortfall in as many digits as it takes, never "2.0 seed lengths, under 2".
TEST(RigChecks, ASizeAHairUnderItsMinimumReadsAsUnderIt) {
  const std::string clump = (std::filesystem::temp_directory_path() / "seedcal-rig-check-hair.txt").string();
  const double height_m = 0.02;
  // Diameter 10.0002 mm: 0.02 m is 1.99996 seed lengths.
  std::ofstream(clump) << "0.0 0.0 0.0 " << 0.5 * 0.0100002 << "\n";
  const auto w = rig_warnings("direct_shear", {"fidelity=quick", "particle.clump_file=" + clump, "particle.scale_sd=0",
                                               "direct_shear.quick.sample_height_m=" + std::to_string(height_m)});
  std::string height;
  for (const std::string& x : w)
    if (x.find("direct_shear.quick.sample_height_m is small") != std::string::npos) height = x;
  ASSERT_FALSE(height.empty()) << ::testing::PrintToString(w);
  EXPECT_EQ(height.find("2.0 seed lengths"), std::string::npos) << height;
  EXPECT_NE(height.find("1.9999"), std::string::npos) << height;
  EXPECT_EQ(height.find("at least 0.02 m"), std::string::npos) << height;
  std::filesystem::remove(clump);
}

// The paper's 61.8 mm box against the larger Jinong 2 seeds (12.8 mm long, 4.8 lengths): the
// shipped scene warns.
TEST(RigChecks, ThePapersBoxIsSmallForJinong2) {
  const auto w = check_scene(load_scene_file("data/scenes/jinong2/direct_shear.toml", {"fidelity=paper"}));
  bool diameter = false;
  for (const std::string& x : w) diameter = diameter || x.find("direct_shear.paper.diameter_m is small") != std::string::npos;
  EXPECT_TRUE(diameter) << ::testing::PrintToString(w);
}

TEST(RigChecks, ShippedJinong1ScenesWithTheirOwnSeedsDrawNoWarning) {
  for (const char* scene : {"direct_shear", "piling", "bulk_density", "drum"})
    for (const char* fidelity : {"quick", "paper"}) {
      const auto w = rig_warnings(scene, {std::string("fidelity=") + fidelity});
      EXPECT_TRUE(w.empty()) << scene << " " << fidelity << ": " << ::testing::PrintToString(w);
    }
}

}  // namespace
}  // namespace seedcal
