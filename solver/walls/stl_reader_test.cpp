// STL reader: binary and ASCII round trips, unit scaling, and bad files rejected with a message
// naming the file.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>

#include "solver/core/errors.hpp"
#include "solver/walls/mesh_shape.hpp"
#include "solver/walls/stl_reader.hpp"

namespace seedcal {
namespace {

const std::vector<Triangle> kTris = {
    {Vec3(0, 0, 0), Vec3(10, 0, 0), Vec3(0, 10, 0)},
    {Vec3(10, 0, 0), Vec3(10, 10, 0.5), Vec3(0, 10, 0)},
    {Vec3(-1.25, 3.0e-3, 7), Vec3(2, 4, 6.125), Vec3(1e-7, -5, 0.1)}};

std::string temp_path(const std::string& name) { return ::testing::TempDir() + "seedcal_stl_" + name; }

void write(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

std::string binary_stl(const std::vector<Triangle>& tris, const char* header = "binary test") {
  std::string b(80, ' ');
  std::memcpy(b.data(), header, std::strlen(header));
  const auto n = static_cast<std::uint32_t>(tris.size());
  for (int k = 0; k < 4; ++k) b.push_back(static_cast<char>((n >> (8 * k)) & 0xff));
  for (const Triangle& t : tris) {
    float f[12] = {0, 0, 1};  // a normal (ignored by the reader)
    for (int v = 0; v < 3; ++v)
      for (int d = 0; d < 3; ++d) f[3 + 3 * v + d] = static_cast<float>(t[static_cast<std::size_t>(v)][d]);
    b.append(reinterpret_cast<const char*>(f), sizeof f);  // little-endian host (x86-64, aarch64)
    b.append(2, '\0');                                     // attribute byte count
  }
  return b;
}

std::string ascii_stl(const std::vector<Triangle>& tris) {
  std::string s = "solid test\n";
  char line[200];
  for (const Triangle& t : tris) {
    s += "  facet normal 0 0 1\n    outer loop\n";
    for (const Vec3& v : t) {
      std::snprintf(line, sizeof line, "      vertex %.17g %.17g %.17g\n", v.x(), v.y(), v.z());
      s += line;
    }
    s += "    endloop\n  endfacet\n";
  }
  return s + "endsolid test\n";
}

TEST(StlReader, BinaryRoundTripIsExactInSinglePrecision) {
  const std::string p = temp_path("round.stl");
  // A header starting with "solid", as some exporters write: the size decides it is binary.
  write(p, binary_stl(kTris, "solid but binary"));
  const auto t = read_stl(p);
  ASSERT_EQ(t.size(), kTris.size());
  for (std::size_t k = 0; k < t.size(); ++k)
    for (std::size_t v = 0; v < 3; ++v)
      for (int d = 0; d < 3; ++d)  // floats in the file: the value rounded once to binary32
        EXPECT_EQ(t[k][v][d], static_cast<double>(static_cast<float>(kTris[k][v][d])));
  std::remove(p.c_str());
}

TEST(StlReader, AsciiRoundTripIsExactAndScaled) {
  const std::string p = temp_path("round_ascii.stl");
  write(p, ascii_stl(kTris));
  const auto t = read_stl(p);
  ASSERT_EQ(t.size(), kTris.size());
  for (std::size_t k = 0; k < t.size(); ++k)
    for (std::size_t v = 0; v < 3; ++v) EXPECT_EQ(t[k][v], kTris[k][v]);  // %.17g round-trips
  const auto mm = read_stl(p, 1e-3);  // a file in millimetres
  EXPECT_DOUBLE_EQ(mm[0][1].x(), 0.01);
  // Into a mesh wall: 3 triangles, the first two share an edge (welded vertices).
  const TriangleMeshShape m = TriangleMeshShape::from_stl(p, 1e-3);
  EXPECT_EQ(m.primitive_count(), 3);
  EXPECT_EQ(m.vertex_count(), 7u);
  std::remove(p.c_str());
}

// The message names the file and says what is wrong.
void expect_rejected(const std::string& name, const std::string& bytes, const std::string& why) {
  const std::string p = temp_path(name);
  write(p, bytes);
  try {
    read_stl(p);
    ADD_FAILURE() << name << " was accepted";
  } catch (const SettingError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(p), std::string::npos) << m;
    EXPECT_NE(m.find(why), std::string::npos) << m;
    EXPECT_EQ(e.key(), p);
  }
  std::remove(p.c_str());
}

TEST(StlReader, RejectsBadFilesNamingThem) {
  expect_rejected("empty.stl", "", "empty");
  expect_rejected("text.stl", "hello world, not a mesh\n", "neither a binary STL");
  std::string truncated = binary_stl(kTris);
  truncated.resize(truncated.size() - 7);
  expect_rejected("truncated.stl", truncated, "neither a binary STL");
  expect_rejected("no_triangles.stl", "solid x\nendsolid x\n", "no triangles");
  expect_rejected("zero_binary.stl", binary_stl({}), "no triangles");
  expect_rejected("two_vertices.stl",
                  "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid\n",
                  "exactly 3 vertices");
  expect_rejected("bad_number.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 zero 0\n",
                  "needs 3 numbers");
  expect_rejected("unterminated.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n", "truncated");
  std::vector<Triangle> nan = kTris;
  nan[1][2].x() = std::nan("");
  expect_rejected("nan.stl", binary_stl(nan), "non-finite");
  try {
    read_stl(temp_path("does_not_exist.stl"));
    ADD_FAILURE() << "a missing file was accepted";
  } catch (const SettingError& e) {
    EXPECT_NE(std::string(e.what()).find("does_not_exist.stl: cannot open"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace seedcal
