// The export's writers (docs/export.md): the CSV read back gives the clump and the values it was
// written from, and its keys re-applied to the scene give the same model; the LIGGGHTS fragment
// holds the template and the property tables; the headers state what does not carry over.
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>
#include <utility>

#include <gtest/gtest.h>

#include "calibrate/clumps/clump_file.hpp"
#include "calibrate/export/csv_export.hpp"
#include "calibrate/export/export_notes.hpp"
#include "calibrate/export/finished_study.hpp"
#include "calibrate/export/liggghts_deck.hpp"
#include "solver/clump/mass_properties.hpp"
#include "store/errors.hpp"

namespace seedcal {
namespace {

// The shipped bulk-density scene: Table 6 values, the nine-sphere Jinong 1 clump, CDT with the
// centre-of-mass lever, a size spread of sd 0.1308 (data/scenes/jinong1/bulk_density.toml).
const char* kScene = "data/scenes/jinong1/bulk_density.toml";

std::vector<std::vector<std::string>> read_csv(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> row;
    std::string cell;
    bool quoted = false;
    for (char c : line) {
      if (c == '"') quoted = !quoted;
      else if (c == ',' && !quoted) row.push_back(std::exchange(cell, std::string()));
      else cell += c;
    }
    row.push_back(cell);
    rows.push_back(row);
  }
  return rows;
}

std::map<std::string, std::string> parameter_map(const ExportedModel& m) {
  const auto rows = read_csv(parameters_csv(m));
  EXPECT_EQ(rows.at(0), (std::vector<std::string>{"key", "value", "unit", "meaning"}));
  std::map<std::string, std::string> out;
  for (std::size_t r = 1; r < rows.size(); ++r) {
    EXPECT_EQ(rows[r].size(), 4u) << rows[r][0];
    out[rows[r][0]] = rows[r][1];
  }
  return out;
}

TEST(ExportCsv, SpheresReadBackToTheClumpAndItsVolume) {
  const ExportedModel m = exported_model_from_scene(kScene, {});
  const auto rows = read_csv(spheres_csv(m));
  ASSERT_EQ(rows.at(0), (std::vector<std::string>{"sphere", "x_m", "y_m", "z_m", "radius_m"}));
  ASSERT_EQ(rows.size(), 1 + m.seeds.body.spheres.size());
  ASSERT_EQ(m.seeds.body.spheres.size(), 9u);  // jinong1-manual-9
  std::vector<SphereXYZR> spheres;
  for (std::size_t r = 1; r < rows.size(); ++r) {
    const SphereDef& s = m.seeds.body.spheres[r - 1];
    const SphereXYZR back{Vec3(std::stod(rows[r][1]), std::stod(rows[r][2]), std::stod(rows[r][3])),
                          std::stod(rows[r][4])};
    // Written with as many digits as a double needs: the same numbers come back.
    EXPECT_EQ(back.centre_m, s.offset_m);
    EXPECT_EQ(back.radius_m, s.radius_m);
    spheres.push_back(back);
  }
  // The spheres as read back enclose the clump file's volume (its [mass_properties], computed when
  // it was built), within the two estimates' stated bounds (1e-4 each, mass_properties.hpp).
  const ClumpModel file = read_clump_file("data/clumps/jinong1-manual-9.toml");
  const UnionMassProperties u = union_mass_properties(spheres, 1e-5);
  EXPECT_NEAR(u.volume_m3 / file.volume_m3, 1.0, 2e-4);
  // Principal frame: the centre of mass at the origin (to the union's own tolerance, 1e-5 of the
  // clump's size).
  EXPECT_LT(u.centroid_m.norm(), 1e-5 * 2.0 * m.bounding_radius_m());

  const auto p = parameter_map(m);
  EXPECT_EQ(std::stoi(p.at("clump.spheres")), 9);
  const double volume = std::stod(p.at("clump.volume_m3"));
  EXPECT_NEAR(volume / u.volume_m3, 1.0, 2e-4);
  EXPECT_DOUBLE_EQ(std::stod(p.at("clump.mass_kg")), volume * 1340.0);
  // d = (6 V / pi)^(1/3): for the Jinong 1 seed about 8.85 mm (its axes 9.63 x 9.11 x 7.94 mm).
  const double d = std::stod(p.at("clump.volume_equivalent_diameter_m"));
  EXPECT_NEAR(d, std::cbrt(6.0 * volume / std::numbers::pi), 1e-15);
  EXPECT_NEAR(d, 8.85e-3, 0.05e-3);
  EXPECT_EQ(std::stod(p.at("clump.principal_inertia_x_kg_m2")), m.seeds.body.principal_inertia_kg_m2.x());
}

TEST(ExportCsv, ParametersAreTheSceneValuesUnderTheirConfigKeys) {
  const ExportedModel m = exported_model_from_scene(kScene, {"seed_seed.static_friction=0.7321"});
  const auto p = parameter_map(m);
  // data/scenes/jinong1/bulk_density.toml and its variety (Table 6), the override in place.
  EXPECT_EQ(p.at("materials.seed.youngs_modulus_pa"), "1.65e+08");
  EXPECT_EQ(p.at("materials.seed.poisson_ratio"), "0.4");
  EXPECT_EQ(p.at("materials.steel.youngs_modulus_pa"), "2e+10");
  EXPECT_EQ(p.at("seed_seed.static_friction"), "0.7321");
  EXPECT_EQ(p.at("seed_seed.restitution"), "0.45");
  EXPECT_EQ(p.at("seed_steel.rolling_friction"), "0.05");
  EXPECT_EQ(p.at("contact.model"), "hertz_mindlin");
  EXPECT_EQ(p.at("contact.rolling"), "cdt");
  EXPECT_EQ(p.at("contact.rolling_lever"), "centre_of_mass");
  // The variety's Table 5: width sd / mean width (data/varieties/jinong1.toml), printed to 16 digits.
  EXPECT_NEAR(std::stod(p.at("particle.scale_sd")), 1.1916e-3 / 9.1098e-3, 1e-15);
  EXPECT_EQ(p.at("gravity_m_s2"), "[0, 0, -9.81]");

  // Every key but clump.* is a --set of the scene: applied to it under other values, they give the
  // exported model back.
  std::vector<std::string> sets = {"seed_seed.static_friction=0.2", "contact.rolling=epsd", "contact.model=hmnr",
                                   "materials.seed.youngs_modulus_pa=1e7"};
  for (const auto& [key, value] : p)
    if (key.rfind("clump.", 0) != 0) sets.push_back(key + "=" + value);
  const ExportedModel back = exported_model_from_scene(kScene, sets);
  EXPECT_EQ(parameters_csv(back), parameters_csv(m));
}

TEST(ExportLiggghts, FragmentHoldsTheTemplateAndThePropertyTables) {
  const ExportedModel m = exported_model_from_scene(kScene, {});
  const std::string f = liggghts_fragment(m);
  // Atom types: 1 = seed, 2 = steel; tables row by row; steel-steel has no interaction (placeholder).
  EXPECT_NE(f.find("youngsModulus peratomtype 1.65e+08 2e+10\n"), std::string::npos) << f;
  EXPECT_NE(f.find("poissonsRatio peratomtype 0.4 0.3\n"), std::string::npos);
  EXPECT_NE(f.find("coefficientRestitution peratomtypepair 2 0.45 0.65 0.65 0.5\n"), std::string::npos);
  EXPECT_NE(f.find("coefficientFriction peratomtypepair 2 0.55 0.4 0.4 0.5\n"), std::string::npos);
  EXPECT_NE(f.find("coefficientRollingFriction peratomtypepair 2 0.05 0.05 0.05 0\n"), std::string::npos);
  EXPECT_NE(f.find("variable seedcal_contact string \"model hertz tangential history rolling_friction cdt\"\n"),
            std::string::npos);
  EXPECT_NE(f.find("pair_style gran ${seedcal_contact}\n"), std::string::npos);
  // The template: the spheres as written read back exactly, then the exact mass and inertia.
  const std::size_t start = f.find("spheres &\n");
  ASSERT_NE(start, std::string::npos);
  std::istringstream in(f.substr(start + 10));
  const BodyDef& b = m.seeds.body;
  for (const SphereDef& s : b.spheres) {
    double x, y, z, r;
    std::string amp;
    ASSERT_TRUE(in >> x >> y >> z >> r >> amp);
    EXPECT_EQ(Vec3(x, y, z), s.offset_m);
    EXPECT_EQ(r, s.radius_m);
    EXPECT_EQ(amp, "&");
  }
  std::string rest;
  std::getline(in >> std::ws, rest);
  EXPECT_EQ(rest, "type 1 mass " + exact_number_text(b.mass_kg) + " inertia_tensor " +
                      exact_number_text(b.principal_inertia_kg_m2.x()) + " 0 0 " +
                      exact_number_text(b.principal_inertia_kg_m2.y()) + " 0 " +
                      exact_number_text(b.principal_inertia_kg_m2.z()) + " use_density");
  EXPECT_NE(f.find("nspheres 9 "), std::string::npos);
  EXPECT_NE(f.find("density constant 1340 "), std::string::npos);
}

TEST(ExportLiggghts, RollingModelsMapToTheirLiggghtsNames) {
  const std::string none = liggghts_fragment(exported_model_from_scene(kScene, {"contact.rolling=none"}));
  EXPECT_NE(none.find("string \"model hertz tangential history\"\n"), std::string::npos);
  EXPECT_EQ(none.find("coefficientRollingFriction"), std::string::npos);
  const std::string epsd = liggghts_fragment(
      exported_model_from_scene(kScene, {"contact.rolling=epsd", "contact.epsd_damping_ratio=0.25"}));
  EXPECT_NE(epsd.find("rolling_friction epsd\"\n"), std::string::npos);
  EXPECT_NE(epsd.find("coefficientRollingViscousDamping peratomtypepair 2 0.25 0.25 0.25 0.25\n"), std::string::npos);
  const std::string clipped = liggghts_fragment(exported_model_from_scene(kScene, {"contact.clip_attractive=true"}));
  EXPECT_NE(clipped.find("rolling_friction cdt limitForce on\"\n"), std::string::npos);
}

TEST(ExportNotes, HeadersStateWhatDoesNotCarryOver) {
  const auto has = [](const std::vector<std::string>& notes, const std::string& text) {
    for (const auto& n : notes)
      if (n.find(text) != std::string::npos) return true;
    return false;
  };
  const ExportedModel cdt = exported_model_from_scene(kScene, {});
  const auto n = carry_over_notes(cdt);
  EXPECT_TRUE(has(n, "relative spin"));
  EXPECT_TRUE(has(n, "rolling_lever = centre_of_mass"));
  EXPECT_TRUE(has(n, "Size spread"));  // scale_sd 0.1308
  EXPECT_FALSE(has(n, "HMNR"));
  const auto hmnr = carry_over_notes(exported_model_from_scene(kScene, {"contact.model=hmnr", "particle.scale_sd=0"}));
  EXPECT_TRUE(has(hmnr, "HMNR"));
  EXPECT_TRUE(has(hmnr, "no LIGGGHTS equivalent"));
  EXPECT_FALSE(has(hmnr, "Size spread"));
  // Every file carries them (comment lines wrap, so look for a short phrase).
  for (const std::string& text : {liggghts_fragment(cdt), liggghts_settle_deck(cdt, default_settle_deck(cdt)),
                                   spheres_csv(cdt), parameters_csv(cdt)}) {
    EXPECT_NE(text.find("What does not carry over exactly"), std::string::npos);
    EXPECT_NE(text.find("relative spin"), std::string::npos);
  }
}

TEST(ExportLiggghts, SettleDeckDefaultsFollowTheClump) {
  const ExportedModel m = exported_model_from_scene(kScene, {});
  const SettleDeck d = default_settle_deck(m, 250);
  // Six bounding diameters, whole millimetres.
  EXPECT_DOUBLE_EQ(d.box_x_m, std::ceil(12.0 * m.bounding_radius_m() * 1000.0) / 1000.0);
  // Walls three bed heights tall (the bed at a solid fraction of 0.5), the pour from 0.3 of it.
  const double bed = 250 * m.volume_m3() / (0.5 * d.box_x_m * d.box_y_m);
  EXPECT_NEAR(d.wall_height_m, 3.0 * bed, 1e-15);
  EXPECT_NEAR(d.insert_lo_z_m, 0.3 * bed, 1e-15);
  EXPECT_EQ(d.insert_hi_z_m, d.wall_height_m);
  EXPECT_EQ(d.dt_s, exported_time_step_s(m, std::sqrt(2.0 * 9.81 * d.wall_height_m)));
  const std::string deck = liggghts_settle_deck(m, d);
  EXPECT_NE(deck.find("variable count index 250\n"), std::string::npos);
  EXPECT_NE(deck.find("include         in.seedcal_model\n"), std::string::npos);
  EXPECT_NE(deck.find("create_box      2 seedcal_domain\n"), std::string::npos);
  EXPECT_NE(deck.find("primitive type 2 zplane 0.0\n"), std::string::npos);  // a steel floor
}

TEST(ExportedModel, ASceneWithoutSeedsIsRefused) {
  try {
    exported_model_from_scene("data/scenes/examples/impact.toml", {});
    FAIL() << "an impact scene has no [particle] seed";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no [particle] seed"), std::string::npos) << e.what();
  }
}

TEST(FinishedStudy, AnUnfinishedOrMissingStudyIsBadInput) {
  const auto dir = std::filesystem::temp_directory_path() / ("seedcal-export-test-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto message = [&](const FinishedStudyOptions& o) {
    try {
      read_finished_study(o);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message({(dir / "nowhere").string(), "", ""}).find("no such directory"), std::string::npos);
  EXPECT_NE(message({dir.string(), "", ""}).find("summary.json: cannot open"), std::string::npos);
  std::ofstream(dir / "summary.json") << R"({"stage_reached": "confirm"})";
  const std::string unfinished = message({dir.string(), "", ""});
  EXPECT_NE(unfinished.find("stage_reached = \"confirm\": the study is not finished"), std::string::npos) << unfinished;
  std::ofstream(dir / "summary.json") << R"({"stage_reached": "done", "calibrated": {}, "held_at_nominal": {}})";
  EXPECT_NE(message({dir.string(), "", ""}).find("provenance.study_file is missing"), std::string::npos);
  std::ofstream(dir / "summary.json") << R"({"stage_reached": "done", "calibrated": {"a": "x"}})";
  EXPECT_NE(message({dir.string(), "", ""}).find("calibrated.a is not a number"), std::string::npos);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace seedcal
