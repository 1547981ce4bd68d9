// A scene's seed values from its variety (variety_scene.hpp): what the variety supplies, what the
// scene file and --set replace, the clump model it names, the errors for what is missing; and the
// shipped data: every seed scene in data/ names a variety and repeats none of its values.
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "calibrate/config/variety_scene.hpp"
#include "calibrate/scenes/scene_file.hpp"
#include "store/errors.hpp"
#include "tests/support/cli.hpp"

namespace seedcal {
namespace {

namespace fs = std::filesystem;

std::string data(const std::string& rel) { return testing::source_dir() + "/data/" + rel; }

// A bulk-density scene of its own naming the shipped Jinong 1 variety by its absolute path.
std::string write_scene(const std::string& dir, const std::string& extra, const std::string& variety = "",
                        const std::string& name = "scene.toml") {
  const std::string text = "kind = \"bulk_density\"\nfidelity = \"quick\"\nvariety = \"" +
                           (variety.empty() ? data("varieties/jinong1.toml") : variety) + "\"\n" + extra +
                           "\n[materials.steel]\ndensity_kg_m3 = 7850.0\nyoungs_modulus_pa = 2.0e10\n"
                           "poisson_ratio = 0.3\n\n[bulk_density.quick]\ncontainer_m = [0.06, 0.06, 0.06]\n"
                           "wall_material = \"steel\"\n";
  testing::write_text(dir + "/" + name, text);
  return dir + "/" + name;
}

const toml::value* interaction(const toml::value& doc, const std::string& name) {
  for (const toml::value& x : doc.at("interaction").as_array())
    if (x.at("name").as_string().str == name) return &x;
  return nullptr;
}

double number(const toml::value& v) { return v.is_floating() ? v.as_floating() : static_cast<double>(v.as_integer()); }

TEST(VarietyScene, SuppliesTheSeedsValuesFromTable6AndTable5) {
  const std::string scene = write_scene(testing::scratch_dir("variety-supplies"), "");
  const SceneFile f = load_scene_file(scene, {});
  const toml::value& seed = f.doc.at("materials").at("seed");
  // data/varieties/jinong1.toml, [simulation] (the paper's Table 6, Jinong 1 column).
  EXPECT_EQ(number(seed.at("density_kg_m3")), 1340.0);
  EXPECT_EQ(number(seed.at("youngs_modulus_pa")), 1.65e8);
  EXPECT_EQ(number(seed.at("poisson_ratio")), 0.4);
  const toml::value* ss = interaction(f.doc, "seed_seed");
  ASSERT_NE(ss, nullptr);
  EXPECT_EQ(number(ss->at("static_friction")), 0.55);
  EXPECT_EQ(number(ss->at("rolling_friction")), 0.05);
  EXPECT_EQ(number(ss->at("restitution")), 0.45);
  // Table 6's steel column, for the one rig material the scene defines.
  const toml::value* st = interaction(f.doc, "seed_steel");
  ASSERT_NE(st, nullptr);
  EXPECT_EQ(number(st->at("restitution")), 0.65);
  EXPECT_EQ(number(st->at("static_friction")), 0.4);
  EXPECT_EQ(interaction(f.doc, "seed_pmma"), nullptr);  // no PMMA in this rig: no interaction
  // Table 5: width sd / mean width.
  EXPECT_DOUBLE_EQ(number(f.doc.at("particle").at("scale_sd")), 1.1916e-3 / 9.1098e-3);
  EXPECT_TRUE(f.variety.replaced.empty());
  EXPECT_TRUE(f.variety.repeated.empty());
  // The default model's clump file.
  EXPECT_EQ(fs::weakly_canonical(scene_clump_file(f.doc, scene)), fs::weakly_canonical(data("clumps/jinong1-manual-9.toml")));
  const auto warnings = check_scene(f);
  for (const std::string& w : warnings) EXPECT_EQ(w.find("replaces"), std::string::npos) << w;
}

TEST(VarietyScene, TheSceneFileAndSetReplaceAValueAndTheFileSaysSo) {
  const std::string scene =
      write_scene(testing::scratch_dir("variety-replaces"), "\n[materials.seed]\nyoungs_modulus_pa = 2.0e8\n");
  const SceneFile f = load_scene_file(scene, {"seed_seed.static_friction=0.8"});
  EXPECT_EQ(number(f.doc.at("materials").at("seed").at("youngs_modulus_pa")), 2.0e8);
  EXPECT_EQ(number(interaction(f.doc, "seed_seed")->at("static_friction")), 0.8);  // --set wins silently
  ASSERT_EQ(f.variety.replaced.size(), 1u);
  EXPECT_NE(f.variety.replaced[0].find("materials.seed.youngs_modulus_pa = 200000000 (scene file) replaces the "
                                       "variety's 165000000"),
            std::string::npos)
      << f.variety.replaced[0];
  const auto warnings = check_scene(f);
  bool said = false;
  for (const std::string& w : warnings) said |= w.find("replaces the variety's") != std::string::npos;
  EXPECT_TRUE(said);
}

TEST(VarietyScene, AModelOfTheVarietyOrASetClumpFile) {
  const std::string dir = testing::scratch_dir("variety-model");
  const std::string scene = write_scene(dir, "\n[particle]\nmodel = \"manual-7\"\n");
  const SceneFile f = load_scene_file(scene, {});
  EXPECT_EQ(fs::weakly_canonical(scene_clump_file(f.doc, scene)), fs::weakly_canonical(data("clumps/jinong1-manual-7.toml")));
  EXPECT_NO_THROW(check_scene(f));
  // A study's model override picks another of the variety's models.
  const std::string plain = write_scene(dir, "", "", "plain.toml");
  const SceneFile g = load_scene_file(plain, {"particle.model=manual-11"});
  EXPECT_EQ(fs::weakly_canonical(scene_clump_file(g.doc, plain)), fs::weakly_canonical(data("clumps/jinong1-manual-11.toml")));
  // An unknown model names the variety's models.
  const SceneFile bad = load_scene_file(scene, {"particle.model=manual-8"});
  try {
    check_scene(bad);
    ADD_FAILURE() << "an unknown model was accepted";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("particle.model"), std::string::npos) << m;
    EXPECT_NE(m.find("manual-8"), std::string::npos) << m;
    EXPECT_NE(m.find("manual-11, manual-7, manual-9"), std::string::npos) << m;
  }
  // model and clump_file together are refused.
  const SceneFile both = load_scene_file(scene, {"particle.clump_file=" + data("clumps/jinong1-manual-9.toml")});
  EXPECT_THROW(check_scene(both), InputError);
}

TEST(VarietyScene, SetVarietyTakesAnotherSeed) {
  const std::string scene = write_scene(testing::scratch_dir("variety-set"), "");
  const SceneFile f = load_scene_file(scene, {"variety=" + data("varieties/jinong2.toml")});
  EXPECT_EQ(number(f.doc.at("materials").at("seed").at("density_kg_m3")), 1270.0);  // Table 6, Jinong 2
  EXPECT_EQ(number(interaction(f.doc, "seed_seed")->at("static_friction")), 0.35);
  EXPECT_EQ(fs::weakly_canonical(scene_clump_file(f.doc, scene)), fs::weakly_canonical(data("clumps/jinong2-manual-11.toml")));
}

// The drum's fill mass follows the seed: its measured bulk density comes from the variety.
TEST(VarietyScene, TheDrumFillsWithTheVarietysBulkDensity) {
  const std::string drum = data("scenes/jinong1/drum.toml");
  const SceneFile j1 = load_scene_file(drum, {});
  EXPECT_EQ(number(j1.doc.at("drum").at("paper").at("bulk_density_kg_m3")), 680.75);  // Jinong 1, section 3.1
  EXPECT_EQ(number(j1.doc.at("drum").at("quick").at("bulk_density_kg_m3")), 680.75);
  const SceneFile j2 = load_scene_file(drum, {"variety=" + data("varieties/jinong2.toml")});
  EXPECT_EQ(number(j2.doc.at("drum").at("paper").at("bulk_density_kg_m3")), 664.62);  // Jinong 2
}

TEST(VarietyScene, AVarietyWithoutAValueTheSceneNeedsIsAnError) {
  const std::string dir = testing::scratch_dir("variety-missing");
  // A variety with dimensions but no Table 6 values: the scene must then give them itself.
  testing::write_text(dir + "/seed.toml",
                      "name = \"mine\"\ndensity_kg_m3 = 1200.0\nmoisture_fraction = 0.1\nthousand_seed_mass_kg = 0.3\n"
                      "[dimensions]\nlength_m = 9e-3\nlength_sd_m = 0.5e-3\nwidth_m = 8e-3\nwidth_sd_m = 0.5e-3\n"
                      "thickness_m = 7e-3\nthickness_sd_m = 0.5e-3\n");
  const std::string scene = write_scene(dir, "", dir + "/seed.toml");
  try {
    load_scene_file(scene, {});
    ADD_FAILURE() << "a missing value was accepted";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("scene.toml"), std::string::npos) << m;
    EXPECT_NE(m.find("seed.toml, which gives no [simulation] youngs_modulus_pa"), std::string::npos) << m;
    EXPECT_NE(m.find("[simulation] static_friction"), std::string::npos) << m;
    EXPECT_EQ(m.find("density_kg_m3"), std::string::npos) << m;  // the variety's measured density serves
  }
  try {  // a variety file that is not there: the scene, the key and where it looked
    load_scene_file(write_scene(dir, "", dir + "/absent.toml", "other.toml"), {});
    ADD_FAILURE() << "a missing variety file was accepted";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("other.toml: variety = \""), std::string::npos) << m;
    EXPECT_NE(m.find("no such variety file"), std::string::npos) << m;
  }
}

// Every seed scene shipped in data/ takes its seed from a variety and repeats none of the values
// the variety holds: one file per seed to edit.
TEST(ShippedScenes, NameAVarietyAndRepeatNoneOfItsValues) {
  int seed_scenes = 0;
  for (const auto& entry : fs::recursive_directory_iterator(data("scenes"))) {
    if (entry.path().extension() != ".toml") continue;
    const std::string file = entry.path().string();
    SCOPED_TRACE(file);
    toml::value doc = toml::parse(file);
    if (!doc.contains("kind") || doc.at("kind").as_string().str == "impact") continue;  // glass spheres, no seed
    ++seed_scenes;
    ASSERT_TRUE(doc.contains("variety")) << file << ": a seed scene names no variety";
    const VarietyDefaults v = apply_variety(doc, file);
    for (const std::string& k : v.repeated) ADD_FAILURE() << file << ": repeats its variety's " << k;
    for (const std::string& k : v.replaced) ADD_FAILURE() << file << ": " << k;
  }
  EXPECT_GE(seed_scenes, 7);  // the five Jinong 1 tests and the Jinong 2 and 3 shear boxes
}

}  // namespace
}  // namespace seedcal
