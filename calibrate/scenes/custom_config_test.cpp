// The custom scene's config (custom_config.hpp, docs/scenes/custom.md): the shipped hopper reads
// and plans; a bad key, a value out of range, a missing mesh file and the other mistakes a user
// makes are refused naming the file, the key, the value and what is allowed.
#include <filesystem>
#include <regex>
#include <string>

#include <gtest/gtest.h>

#include "calibrate/scenes/scene_file.hpp"
#include "store/errors.hpp"

namespace seedcal {
namespace {

namespace fs = std::filesystem;

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The shipped hopper with its relative paths made absolute, so that it can be written elsewhere.
std::string hopper_text() {
  const fs::path dir = fs::absolute("data/scenes/examples");
  std::string t = read_text((dir / "hopper.toml").string());
  t = std::regex_replace(t, std::regex("\"hopper_cone.stl\""), "\"" + (dir / "hopper_cone.stl").string() + "\"");
  t = std::regex_replace(t, std::regex("\"../../varieties/"), "\"" + fs::absolute("data/varieties").string() + "/");
  return t;
}

// Every problem the config check reports for `text`, one per line ("" when it passes).
std::string problems(const std::string& text, const std::string& name) {
  const fs::path path = fs::temp_directory_path() / ("seedcal-custom-" + name + ".toml");
  std::ofstream(path) << text;
  std::string out;
  try {
    check_scene(load_scene_file(path.string(), {"fidelity=quick"}));
  } catch (const InputError& e) {
    for (const std::string& p : e.problems()) out += p + "\n";
  }
  fs::remove(path);
  return out;
}

std::string replaced(const std::string& text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at == std::string::npos) return text;
  return text.substr(0, at) + to + text.substr(at + from.size());
}

bool has(const std::string& all, const std::string& part) { return all.find(part) != std::string::npos; }

TEST(CustomConfig, TheShippedHopperReadsAndPlansItsThreePhases) {
  EXPECT_EQ(problems(hopper_text(), "ok"), "");
  const RunPlan p = plan_scene(load_scene_file("data/scenes/examples/hopper.toml", {"fidelity=quick"}));
  ASSERT_EQ(p.phases.size(), 3u);
  EXPECT_EQ(p.phases[0].name, "fill");
  EXPECT_EQ(p.phases[1].name, "settle");
  EXPECT_EQ(p.phases[2].name, "run");
  EXPECT_EQ(p.phases[2].simulated_s, 0.5);  // the quick table's run_time_s, exact
  // 0.3 kg of seeds of 0.487 g (the clump file's mass) x E[s^3] = 1.051 (scale_sd 0.1308): ~586.
  EXPECT_NEAR(p.seeds, 0.3 / (0.000486750685 * 1.0513), 2.0);
  EXPECT_GT(p.dt_s, 0.0);
}

TEST(CustomConfig, AnUnknownKeyIsRefusedWithASuggestion) {
  const std::string all = problems(replaced(hopper_text(), "stop_s = 0.07", "stop_at_s = 0.07"), "unknown");
  EXPECT_TRUE(has(all, "custom.wall[2].stop_at_s is not a known key (did you mean \"stop_s\"?)")) << all;
  EXPECT_TRUE(has(all, "seedcal-custom-unknown.toml:")) << all;
}

TEST(CustomConfig, AValueOutOfRangeNamesTheKeyValueAndRange) {
  const std::string all = problems(replaced(hopper_text(), "radius_m = 0.075", "radius_m = -0.075"), "range");
  EXPECT_TRUE(has(all, "custom.wall[1].radius_m = -0.075: must be in [0.0001, 100]")) << all;
  const std::string run = problems(replaced(hopper_text(), "run_time_s = 0.5", "run_time_s = 0"), "run-time");
  EXPECT_TRUE(has(run, "custom.quick.run_time_s = 0: must be in (0, 1000]")) << run;
}

TEST(CustomConfig, AMissingMeshFileIsNamed) {
  const std::string all = problems(std::regex_replace(hopper_text(), std::regex("\"[^\"]*hopper_cone.stl\""),
                                                      "\"no_such_hopper.stl\""),
                                   "mesh");
  EXPECT_TRUE(has(all, "custom.wall[0].file")) << all;
  EXPECT_TRUE(has(all, "no_such_hopper.stl")) << all;
  EXPECT_TRUE(has(all, "no such file")) << all;
}

TEST(CustomConfig, OtherMistakesAreEachNamed) {
  std::string t = hopper_text();
  t = replaced(t, "kind = \"discharge_rate\"", "kind = \"discharge\"");
  t = replaced(t, "fill_mass_kg = 0.3", "fill_mass_kg = 0.3\nfill_count = 100");
  t = replaced(t, "start_s = 0.0", "start_s = 0.3");  // after stop_s = 0.2
  t = replaced(t, "region_hi_m = [0.045, 0.045, 0.12]", "region_hi_m = [0.045, -0.05, 0.22]");
  t = replaced(t, "shape = \"cylinder\"", "shape = \"cone\"");
  t = replaced(t, "to_m = [0.07, 0.0, 0.0]", "to_m = [0.07, 0.0, 0.01]");
  t = replaced(t, "name = \"hopper\"", "name = \"Hopper mass\"");
  t = replaced(t, "material = \"steel\"\nmotion", "material = \"brass\"\nmotion");
  const std::string all = problems(t, "mistakes");
  EXPECT_TRUE(has(all, "custom.measure[0].kind = \"discharge\"")) << all;
  EXPECT_TRUE(has(all, "custom.quick.fill_mass_kg give exactly one of fill_mass_kg or fill_count")) << all;
  EXPECT_TRUE(has(all, "custom.wall[2].stop_s must be after start_s")) << all;
  EXPECT_TRUE(has(all, "custom.fill.region_hi_m must be above region_lo_m")) << all;
  EXPECT_TRUE(has(all, "custom.wall[1].shape = \"cone\"")) << all;
  EXPECT_TRUE(has(all, "custom.measure[2].to_m must be at the height of from_m")) << all;
  EXPECT_TRUE(has(all, "custom.measure[1].name must be lower-case")) << all;
  EXPECT_TRUE(has(all, "custom.wall[2].material")) << all;
  EXPECT_TRUE(has(all, "brass")) << all;
}

TEST(CustomConfig, EveryShapeAndMotionReads) {
  std::string t = hopper_text();
  // A floor plane, a turning box and a mesh in metres scaled by 1e-3 (the same cone).
  t = replaced(t, "[custom.fill]", R"([[custom.wall]]
name = "floor"
shape = "plane"
origin_m = [0.0, 0.0, -0.3]
normal = [0.0, 0.0, 1.0]
material = "steel"

[[custom.wall]]
name = "paddle"
shape = "box"
origin_m = [0.2, 0.2, 0.0]
size_m = [0.01, 0.05, 0.05]
material = "steel"
motion = "rotate"
axis = [0.0, 0.0, 1.0]
axis_point_m = [0.2, 0.2, 0.0]
rate_rpm = 30.0
start_s = 0.1

[[custom.wall]]
name = "cone_m"
shape = "mesh"
file = "FILE"
unit = "m"
scale = 1e-3
origin_m = [0.5, 0.0, 0.0]
material = "steel"

[custom.fill])");
  t = replaced(t, "\"FILE\"", "\"" + fs::absolute("data/scenes/examples/hopper_cone.stl").string() + "\"");
  EXPECT_EQ(problems(t, "shapes"), "");
}

}  // namespace
}  // namespace seedcal
