// A scene's schema declaration (scene_schema.hpp): it reads every key it declares into the spec,
// keeps the spec's own default for an absent key, rejects a value outside its range naming the
// file, key, value and range, reports an undeclared key as unknown, and refuses a metric it does
// not declare; the docs tables list exactly the declared keys with the spec's defaults.
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "calibrate/scenes/scene_schema.hpp"
#include "store/errors.hpp"

namespace seedcal {
namespace {

enum class Shape { round, flat };

struct ToySpec {
  std::uint16_t wall_material = 0;
  double width_m = 0.25;
  int sectors = 8;
  bool fixed = false;
  Shape shape = Shape::round;
  Eigen::Vector3d box_m = Eigen::Vector3d(0.1, 0.2, 0.3);
  std::vector<double> times_s = {1.0, 2.0};
};

SceneSchema<ToySpec> toy_schema() {
  SceneSchema<ToySpec> s("toy", "`[toy]`");
  s.material("wall_material", &ToySpec::wall_material, "the seeds touch the wall", "the wall's material")
      .number("width_m", &ToySpec::width_m, Range::left_open(0.0, 1.0), "m", "width")
      .integer("sectors", &ToySpec::sectors, 2, 72, "sectors")
      .flag("fixed", &ToySpec::fixed, "held")
      .choice("shape", &ToySpec::shape, {{"round", Shape::round}, {"flat", Shape::flat}}, "shape")
      .vec3("box_m", &ToySpec::box_m, Range::closed(0.01, 1.0), false, "m", "box")
      .numbers("times_s", &ToySpec::times_s, Range::closed(0.0, 10.0), 1, 5, "s", "times");
  s.metric("toy_index_m", "m", "the index");
  return s;
}

// The physics part of a config with a seed material and a steel one that interact.
const char* kPhysics = R"(
[materials.seed]
density_kg_m3 = 1000.0
youngs_modulus_pa = 1e8
poisson_ratio = 0.3
[materials.steel]
density_kg_m3 = 7850.0
youngs_modulus_pa = 2e10
poisson_ratio = 0.3
[[interaction]]
between = ["seed", "steel"]
restitution = 0.5
static_friction = 0.4
rolling_friction = 0.05
)";

// Reads `toy_table` (the body of [toy]) with the schema; returns the spec, or throws InputError.
ToySpec read_toy(const std::string& toy_table) {
  std::istringstream text(std::string(kPhysics) + "[toy]\n" + toy_table);
  const toml::value doc = toml::parse(text, "toy.toml");
  auto diag = std::make_shared<ConfigDiagnostics>();
  diag->file = "toy.toml";
  TomlReader root(doc, "", diag);
  const PhysicsConfig phys = read_physics(root);
  ToySpec spec;
  auto rig = root.table("toy");
  toy_schema().read(*rig, {phys, phys.material_index.at("seed")}, spec);
  rig->check_unknown_keys();
  root.diagnostics().throw_if_any();
  return spec;
}

TEST(SceneSchema, ReadsEveryDeclaredKey) {
  const ToySpec s = read_toy(
      "wall_material = \"steel\"\nwidth_m = 0.5\nsectors = 4\nfixed = true\nshape = \"flat\"\n"
      "box_m = [0.5, 0.6, 0.7]\ntimes_s = [3.0]\n");
  EXPECT_EQ(s.wall_material, 1);
  EXPECT_EQ(s.width_m, 0.5);
  EXPECT_EQ(s.sectors, 4);
  EXPECT_TRUE(s.fixed);
  EXPECT_EQ(s.shape, Shape::flat);
  EXPECT_EQ(s.box_m, Eigen::Vector3d(0.5, 0.6, 0.7));
  EXPECT_EQ(s.times_s, std::vector<double>{3.0});
}

TEST(SceneSchema, AnAbsentKeyKeepsTheSpecsDefault) {
  const ToySpec s = read_toy("wall_material = \"steel\"\n");
  const ToySpec d;
  EXPECT_EQ(s.width_m, d.width_m);
  EXPECT_EQ(s.sectors, d.sectors);
  EXPECT_EQ(s.fixed, d.fixed);
  EXPECT_EQ(s.shape, d.shape);
  EXPECT_EQ(s.box_m, d.box_m);
  EXPECT_EQ(s.times_s, d.times_s);
}

// The message an InputError of read_toy(table) carries (all its problems), or "" when it reads.
std::string problems_of(const std::string& table) {
  try {
    read_toy(table);
  } catch (const InputError& e) {
    std::string all;
    for (const std::string& p : e.problems()) all += p + "\n";
    return all;
  }
  return "";
}

TEST(SceneSchema, BadValuesNameTheFileKeyValueAndRange) {
  const std::string p = problems_of("wall_material = \"steel\"\nwidth_m = 1.5\nsectors = 100\nshape = \"square\"\n");
  EXPECT_NE(p.find("toy.toml"), std::string::npos) << p;
  EXPECT_NE(p.find("toy.width_m = 1.5"), std::string::npos) << p;
  EXPECT_NE(p.find("(0, 1]"), std::string::npos) << p;
  EXPECT_NE(p.find("toy.sectors = 100"), std::string::npos) << p;
  EXPECT_NE(p.find("toy.shape"), std::string::npos) << p;
  EXPECT_NE(p.find("round"), std::string::npos) << p;  // the allowed words
  // A material is required, and must be one of [materials].
  EXPECT_NE(problems_of("width_m = 0.5\n").find("toy.wall_material"), std::string::npos);
  EXPECT_NE(problems_of("wall_material = \"glass\"\n").find("glass"), std::string::npos);
  // An undeclared key is unknown, with the declared key it most resembles.
  const std::string u = problems_of("wall_material = \"steel\"\nwidht_m = 0.5\n");
  EXPECT_NE(u.find("widht_m"), std::string::npos) << u;
  EXPECT_NE(u.find("width_m"), std::string::npos) << u;
}

TEST(SceneSchema, AMaterialWithoutInteractionIsAnError) {
  const std::string p = problems_of("wall_material = \"seed\"\n");  // seed-seed has no [[interaction]]
  EXPECT_NE(p.find("toy.wall_material"), std::string::npos) << p;
  EXPECT_NE(p.find("the seeds touch the wall"), std::string::npos) << p;
}

TEST(SceneSchema, UndeclaredMetricsAreRefused) {
  const auto s = toy_schema();
  nlohmann::json j = {{"index_key", "toy_index_m"}, {"toy_index_m", 1.0}, {"cpu_seconds", 0.1}, {"warnings", {}}};
  EXPECT_NO_THROW(s.check_metrics(j));
  j["toy_undeclared"] = 2.0;
  EXPECT_THROW(s.check_metrics(j), std::logic_error);
}

TEST(SceneSchema, DocsTablesListTheDeclaredKeysWithTheSpecsDefaults) {
  const SchemaTable t = toy_schema().doc();
  ASSERT_EQ(t.keys.size(), 7u);
  EXPECT_EQ(t.keys[0].default_text, "required");
  EXPECT_EQ(t.keys[1].default_text, "0.25");
  EXPECT_EQ(t.keys[1].range, "(0, 1]");
  EXPECT_EQ(t.keys[2].range, "2 .. 72");
  EXPECT_EQ(t.keys[3].default_text, "false");
  EXPECT_EQ(t.keys[4].range, "round / flat");
  EXPECT_EQ(t.keys[4].default_text, "round");
  EXPECT_EQ(t.keys[5].default_text, "0.1, 0.2, 0.3");
  EXPECT_EQ(t.keys[6].default_text, "1, 2");
  const std::string md = keys_markdown(t);
  for (const SchemaKey& k : t.keys) EXPECT_NE(md.find("| `" + k.key + "` |"), std::string::npos) << md;
  EXPECT_NE(metrics_markdown(t).find("| `toy_index_m` | m | the index |"), std::string::npos);
}

TEST(SceneSchema, NumbersAreWrittenInTheirShortestExactForm) {
  EXPECT_EQ(schema_number_text(0.0618), "0.0618");
  EXPECT_EQ(schema_number_text(2e-4), "0.0002");
  EXPECT_EQ(schema_number_text(2e5), "200000");
  EXPECT_EQ(schema_number_text(1e-5), "1e-05");
  EXPECT_EQ(schema_range_text(Range::positive()), "> 0");
  EXPECT_EQ(schema_range_text(Range::open(0.0, 0.9)), "(0, 0.9)");
}

// Every shipped scene kind has a schema whose metrics include its index.
TEST(SceneSchema, EverySeedSceneDeclaresItsKeysAndIndex) {
  const auto tables = scene_schema_tables();
  ASSERT_EQ(tables.size(), 5u);
  for (const SchemaTable& t : tables) {
    EXPECT_FALSE(t.keys.empty()) << t.kind;
    ASSERT_FALSE(t.metrics.empty()) << t.kind;
    EXPECT_NE(t.metrics[0].meaning.find("index"), std::string::npos) << t.kind << ": the first metric is the index";
  }
}

}  // namespace
}  // namespace seedcal
