// PLY and OBJ readers (surface_reader.hpp): a unit cube written as a scanner or a CAD program
// would (ASCII and both binary byte orders, quads and triangles, extra properties and elements,
// slashed and negative OBJ indices) reads back as 12 triangles enclosing exactly its volume; bad
// files are refused with a message naming the file and what is wrong.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>

#include "solver/core/errors.hpp"
#include "solver/walls/surface_reader.hpp"

namespace seedcal {
namespace {

// The unit cube's corners and its six faces as outward quads.
const double kCorner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
const int kQuad[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {2, 3, 7, 6}, {1, 2, 6, 5}, {0, 4, 7, 3}};

// Enclosed volume by the divergence theorem: exact for a closed, consistently oriented surface.
double volume(const std::vector<Triangle>& tris) {
  double v6 = 0.0;
  for (const Triangle& t : tris) v6 += t[0].dot(t[1].cross(t[2]));
  return v6 / 6.0;
}

std::string ascii_ply() {
  std::string s =
      "ply\r\nformat ascii 1.0\r\ncomment made by a scanner\r\nelement vertex 8\r\nproperty float x\r\n"
      "property float y\r\nproperty float z\r\nproperty uchar red\r\nelement face 6\r\n"
      "property list uchar int vertex_indices\r\nelement edge 1\r\nproperty int vertex1\r\nproperty int vertex2\r\n"
      "end_header\r\n";
  for (const auto& c : kCorner) s += std::to_string(c[0]) + " " + std::to_string(c[1]) + " " + std::to_string(c[2]) + " 255\r\n";
  for (const auto& q : kQuad) s += "4 " + std::to_string(q[0]) + " " + std::to_string(q[1]) + " " + std::to_string(q[2]) + " " + std::to_string(q[3]) + "\r\n";
  return s + "0 1\r\n";
}

template <typename T>
void put(std::string& b, T v, bool big_endian) {
  char raw[sizeof(T)];
  std::memcpy(raw, &v, sizeof(T));  // little-endian host (x86-64, aarch64)
  if (big_endian) std::reverse(raw, raw + sizeof(T));
  b.append(raw, sizeof(T));
}

// Doubles for the vertices with a normal before them, quads as uchar + uint lists, triangles split
// by hand for the last face (a file may mix polygon sizes).
std::string binary_ply(bool big_endian) {
  std::string b = std::string("ply\nformat ") + (big_endian ? "binary_big_endian" : "binary_little_endian") +
                  " 1.0\nelement vertex 8\nproperty float nx\nproperty double x\nproperty double y\n"
                  "property double z\nelement face 7\nproperty list uchar uint vertex_indices\nend_header\n";
  for (const auto& c : kCorner) {
    put<float>(b, 0.5f, big_endian);
    for (double x : c) put<double>(b, x, big_endian);
  }
  for (int f = 0; f < 5; ++f) {
    put<std::uint8_t>(b, 4, big_endian);
    for (int k = 0; k < 4; ++k) put<std::uint32_t>(b, static_cast<std::uint32_t>(kQuad[f][k]), big_endian);
  }
  const int* q = kQuad[5];
  for (const auto& tri : {std::array<int, 3>{q[0], q[1], q[2]}, std::array<int, 3>{q[0], q[2], q[3]}}) {
    put<std::uint8_t>(b, 3, big_endian);
    for (int k : tri) put<std::uint32_t>(b, static_cast<std::uint32_t>(k), big_endian);
  }
  return b;
}

std::string obj() {
  std::string s = "# a cube\nmtllib cube.mtl\no cube\n";
  for (const auto& c : kCorner) s += "v " + std::to_string(c[0]) + " " + std::to_string(c[1]) + " " + std::to_string(c[2]) + "\n";
  s += "vt 0 0\nvn 0 0 1\ns off\n";
  // Positive with texture and normal indices, then negative (counting back from the last vertex).
  for (int f = 0; f < 3; ++f)
    s += "f " + std::to_string(kQuad[f][0] + 1) + "/1/1 " + std::to_string(kQuad[f][1] + 1) + "//1 " +
         std::to_string(kQuad[f][2] + 1) + "/1 " + std::to_string(kQuad[f][3] + 1) + "\n";
  for (int f = 3; f < 6; ++f)
    s += "f " + std::to_string(kQuad[f][0] - 8) + " " + std::to_string(kQuad[f][1] - 8) + " " +
         std::to_string(kQuad[f][2] - 8) + " " + std::to_string(kQuad[f][3] - 8) + "\n";
  return s;
}

TEST(SurfaceReader, CubeReadsBackFromEveryFlavour) {
  struct Case {
    const char* what;
    std::vector<Triangle> tris;
    std::size_t triangles;
  };
  const Case cases[] = {{"ascii ply", parse_ply(ascii_ply(), "a.ply"), 12},
                        {"little-endian ply", parse_ply(binary_ply(false), "le.ply"), 12},
                        {"big-endian ply", parse_ply(binary_ply(true), "be.ply"), 12},
                        {"obj", parse_obj(obj(), "c.obj"), 12}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    EXPECT_EQ(c.tris.size(), c.triangles);
    EXPECT_NEAR(volume(c.tris), 1.0, 1e-12);  // outward quads give a positive volume
  }
  // A file in millimetres: every coordinate times 1e-3, the volume times 1e-9.
  EXPECT_NEAR(volume(parse_obj(obj(), "c.obj", 1e-3)), 1e-9, 1e-21);
  EXPECT_NEAR(volume(parse_ply(binary_ply(false), "le.ply", 1e-3)), 1e-9, 1e-21);
}

TEST(SurfaceReader, ReadSurfaceDispatchesByExtension) {
  const std::string dir = ::testing::TempDir();
  std::ofstream(dir + "seedcal_cube.PLY", std::ios::binary) << binary_ply(false);
  std::ofstream(dir + "seedcal_cube.obj") << obj();
  EXPECT_EQ(read_surface(dir + "seedcal_cube.PLY").size(), 12u);
  EXPECT_EQ(read_surface(dir + "seedcal_cube.obj").size(), 12u);
  std::ofstream(dir + "seedcal_cube.off") << "OFF\n";
  try {
    read_surface(dir + "seedcal_cube.off");
    FAIL() << "an .off file was read";
  } catch (const SettingError& e) {
    EXPECT_NE(std::string(e.what()).find(".stl, .ply, .obj"), std::string::npos) << e.what();
  }
}

// Each bad file is refused with its name and the reason in the message.
TEST(SurfaceReader, BadFilesSayWhatIsWrong) {
  auto refused = [](const std::string& bytes, bool ply, const std::string& expect) {
    try {
      ply ? parse_ply(bytes, "bad.file") : parse_obj(bytes, "bad.file");
      ADD_FAILURE() << "accepted: " << expect;
    } catch (const SettingError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find("bad.file"), std::string::npos) << m;
      EXPECT_NE(m.find(expect), std::string::npos) << m;
    }
  };
  std::string ply = ascii_ply();
  refused("solid x\n", true, "not a PLY file");
  refused(ply.substr(0, ply.find("end_header")), true, "no 'end_header'");
  refused("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n",
          true, "no face element");
  refused("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nend_header\n", true, "x, y and z");
  refused("ply\nformat binary_middle_endian 1.0\nend_header\n", true, "allowed ascii");
  refused("ply\nformat ascii 1.0\nelement vertex 3\nproperty fixed x\nend_header\n", true, "unknown property type");
  std::string bad_index = ply;
  bad_index.replace(bad_index.find("4 0 3 2 1"), 9, "4 0 3 2 9");
  refused(bad_index, true, "vertex index 9 outside 0 .. 8 - 1");
  const std::string bin = binary_ply(false);
  refused(bin.substr(0, bin.size() - 3), true, "truncated");
  std::string nan = ply;
  nan.replace(nan.find("1.000000 1.000000 1.000000"), 8, "nan     ");
  refused(nan, true, "not a number");
  refused("v 0 0 0\nv 1 0 0\nf 1 2\n", false, "line 3: a face needs at least 3 vertices");
  refused("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", false, "line 4: the face names vertex 4 of 3");
  refused("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n", false, "vertex 0 of 3");
  refused("v 0 0\n", false, "line 1: 'v x y z' needs three finite numbers");
  refused("v 0 0 0\nf 1 x 1\n", false, "face entry 'x'");
  refused("# nothing\n", false, "no vertices");
  refused("v 0 0 0\n", false, "no faces");
}

}  // namespace
}  // namespace seedcal
