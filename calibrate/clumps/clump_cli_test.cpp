// End to end: `seedcal clump build|info|table` through the binary ($SEEDCAL_BINARY), exit codes and
// JSON keys, and a bad input (exit 2).
#include <array>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <vector>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace {

struct Result {
  int rc;
  std::string out;
};

Result run(const std::string& args) {
  const char* bin = std::getenv("SEEDCAL_BINARY");
  const std::string cmd = std::string(bin ? bin : "build/seedcal") + " " + args + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  std::string out;
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), buf.size(), p)) out += buf.data();
  const int status = pclose(p);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

TEST(ClumpCli, BuildInfoJsonAndTable) {
  const std::string out = (std::filesystem::temp_directory_path() / "seedcal_cli_clump.toml").string();
  Result b = run("clump build --variety jinong1 --method manual --spheres 5 --out " + out);
  ASSERT_EQ(b.rc, 0) << b.out;
  Result i = run("clump info " + out + " --json");
  ASSERT_EQ(i.rc, 0) << i.out;
  const auto j = nlohmann::json::parse(i.out);
  for (const char* k : {"spheres", "volume_m3", "target_volume_m3", "iou", "principal_inertia_kg_m2", "bounding_box_m"})
    EXPECT_TRUE(j.contains(k)) << k;
  EXPECT_EQ(j["spheres"].get<int>(), 5);
  EXPECT_GE(j["iou"].get<double>(), 0.8);
  EXPECT_EQ(j["principal_inertia_kg_m2"].size(), 3u);
  Result t = run("clump table --variety jinong3 --json");
  ASSERT_EQ(t.rc, 0) << t.out;
  const auto tj = nlohmann::json::parse(t.out);
  ASSERT_EQ(tj["rows"].size(), 6u);
  // The bar: the finest automatic model within 10 % of the paper's volume (the ellipsoid of the
  // Table 1 means is itself 5.4 % off the paper's scanned seed, docs/clumps.md), manual ones
  // within 15 % and IoU >= 0.8. Both kinds must be there: a renamed label fails, not passes.
  int finest = 0, manual = 0;
  for (const auto& row : tj["rows"]) {
    if (row["request"] == "--method auto --smoothness 0") {
      ++finest;
      EXPECT_NEAR(row["volume_vs_paper"].get<double>(), 1.0, 0.10);
    }
    if (row["filling"] == "manual") {
      ++manual;
      EXPECT_NEAR(row["volume_vs_paper"].get<double>(), 1.0, 0.15);
      EXPECT_GE(row["iou"].get<double>(), 0.8);
    }
  }
  EXPECT_EQ(finest, 1) << tj.dump(1);
  EXPECT_EQ(manual, 3) << tj.dump(1);  // the paper's manual counts for Jinong 3: 7, 9, 11
}

// A seed-sized ellipsoid (8.7 x 6.0 x 4.5 mm, a Jinong 1 seed's size) as a scanner would write it:
// millimetres, its long axis along the scanner's z, each triangle with its own copies of its
// vertices a nanometre apart (ASCII PLY).
void write_scanned_seed(const std::string& path, bool open_a_hole = false) {
  const int nlat = 16, nlon = 32;
  const double pi = 3.14159265358979323846, semi[3] = {4.35, 3.0, 2.25};
  auto point = [&](double theta, double phi) {
    // x along the length; then turned so that x goes to -z (90 degrees about y) and 30 degrees about z.
    const double x = semi[0] * std::cos(theta), y = semi[1] * std::sin(theta) * std::cos(phi),
                 z = semi[2] * std::sin(theta) * std::sin(phi);
    const double X = z, Y = y, Z = -x;  // about y by 90 degrees
    const double c = std::cos(pi / 6), s = std::sin(pi / 6);
    return std::array<double, 3>{c * X - s * Y + 12.0, s * X + c * Y - 7.0, Z + 30.0};
  };
  std::vector<std::array<std::array<double, 3>, 3>> tris;
  for (int i = 0; i < nlat; ++i)
    for (int j = 0; j < nlon; ++j) {
      const double t0 = pi * i / nlat, t1 = pi * (i + 1) / nlat, p0 = 2 * pi * j / nlon, p1 = 2 * pi * (j + 1) / nlon;
      if (i > 0) tris.push_back({point(t0, p0), point(t1, p0), point(t0, p1)});
      if (i < nlat - 1) tris.push_back({point(t0, p1), point(t1, p0), point(t1, p1)});
    }
  if (open_a_hole) tris.pop_back();
  std::ofstream o(path);
  o.precision(12);
  o << "ply\nformat ascii 1.0\ncomment scanner export\nelement vertex " << 3 * tris.size()
    << "\nproperty double x\nproperty double y\nproperty double z\nelement face " << tris.size()
    << "\nproperty list uchar int vertex_indices\nend_header\n";
  int k = 0;
  for (const auto& t : tris)
    for (const auto& v : t) {
      const double jitter = 1e-6 * std::sin(++k);  // mm
      o << v[0] + jitter << " " << v[1] - jitter << " " << v[2] + jitter << "\n";
    }
  for (std::size_t f = 0; f < tris.size(); ++f) o << "3 " << 3 * f << " " << 3 * f + 1 << " " << 3 * f + 2 << "\n";
}

// clump build --scan: the scan is welded, turned so that x is its length and filled; the clump file
// names it relative to its own folder, so clump info finds it from anywhere.
TEST(ClumpCli, BuildFromAScanInMillimetres) {
  const auto dir = std::filesystem::temp_directory_path() / "seedcal_cli_scan";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "scans");
  const std::string scan = (dir / "scans" / "seed.ply").string();
  write_scanned_seed(scan);
  auto box_of = [](const std::string& clump) {
    const Result i = run("clump info " + clump + " --json");
    EXPECT_EQ(i.rc, 0) << i.out;
    return i.rc == 0 ? nlohmann::json::parse(i.out) : nlohmann::json();
  };
  const std::string aligned = (dir / "clumps" / "seed.toml").string();
  const Result b = run("clump build --scan " + scan + " --unit mm --density 1250 --method auto --spheres 60 --out " + aligned);
  ASSERT_EQ(b.rc, 0) << b.out;
  EXPECT_NE(b.out.find("in its principal frame"), std::string::npos) << b.out;
  const auto j = box_of(aligned);
  // The polyhedron (16 x 32 facets) holds 0.97 .. 1 of the ellipsoid's 4/3 pi abc = 123.0 mm3.
  EXPECT_NEAR(j["target_volume_m3"].get<double>(), 0.985 * 123.0e-9, 0.015 * 123.0e-9) << j.dump(1);
  // The fill's box in the shape's frame: length, width, thickness in that order, each within the
  // 10 % an automatic fill of 60 spheres leaves at the surface.
  const auto bb = j["bounding_box_m"];
  EXPECT_NEAR(bb[0].get<double>(), 8.7e-3, 0.1 * 8.7e-3) << j.dump(1);
  EXPECT_NEAR(bb[1].get<double>(), 6.0e-3, 0.1 * 6.0e-3) << j.dump(1);
  EXPECT_NEAR(bb[2].get<double>(), 4.5e-3, 0.1 * 4.5e-3) << j.dump(1);
  // --align none keeps the scanner's frame: the length stays on z.
  const std::string as_scanned = (dir / "as_scanned.toml").string();
  ASSERT_EQ(run("clump build --scan " + scan + " --unit mm --align none --density 1250 --method auto --spheres 60 --out " +
                as_scanned).rc, 0);
  EXPECT_NEAR(box_of(as_scanned)["bounding_box_m"][2].get<double>(), 8.7e-3, 0.1 * 8.7e-3);
  // The unit is required; an open scan is refused naming the file.
  const Result no_unit = run("clump build --scan " + scan + " --density 1250 --method auto --spheres 60 --out " + aligned);
  EXPECT_EQ(no_unit.rc, 2) << no_unit.out;
  EXPECT_NE(no_unit.out.find("--unit m or --unit mm"), std::string::npos) << no_unit.out;
  const std::string open = (dir / "scans" / "open.ply").string();
  write_scanned_seed(open, true);
  const Result hole = run("clump build --scan " + open + " --unit mm --density 1250 --method auto --spheres 60 --out " + aligned);
  EXPECT_EQ(hole.rc, 2) << hole.out;
  EXPECT_NE(hole.out.find("not closed"), std::string::npos) << hole.out;
  EXPECT_NE(hole.out.find("open.ply"), std::string::npos) << hole.out;
  std::filesystem::remove_all(dir);
}

TEST(ClumpCli, BadInputExitsTwo) {
  EXPECT_EQ(run("clump build --variety jinong1 --method manual --spheres 8 --out /tmp/x.toml").rc, 2);
  EXPECT_EQ(run("clump build --variety nosuch --method auto --smoothness 1 --out /tmp/x.toml").rc, 2);
  EXPECT_EQ(run("clump info /nonexistent/clump.toml").rc, 2);
}

}  // namespace
