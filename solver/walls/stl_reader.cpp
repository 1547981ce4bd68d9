#include "solver/walls/stl_reader.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>

#include "solver/core/errors.hpp"

namespace seedcal {

namespace {

std::uint32_t read_u32_le(const char* p) {
  const auto* b = reinterpret_cast<const unsigned char*>(p);
  return static_cast<std::uint32_t>(b[0]) | (static_cast<std::uint32_t>(b[1]) << 8) |
         (static_cast<std::uint32_t>(b[2]) << 16) | (static_cast<std::uint32_t>(b[3]) << 24);
}

float read_f32_le(const char* p) {
  const std::uint32_t u = read_u32_le(p);
  float f;
  std::memcpy(&f, &u, sizeof f);  // IEEE 754 binary32, as the STL format specifies
  return f;
}

void check_finite(const Vec3& v, const std::string& name, std::size_t triangle) {
  if (!v.allFinite())
    throw SettingError(name, "triangle " + std::to_string(triangle) + " has a non-finite vertex");
}

std::vector<Triangle> parse_binary(const std::string& bytes, const std::string& name, std::uint32_t n,
                                   double scale) {
  std::vector<Triangle> tris;
  tris.reserve(n);
  for (std::uint32_t k = 0; k < n; ++k) {
    const char* p = bytes.data() + 84 + 50ull * k + 12;  // 12 bytes of normal, then 3 vertices
    Triangle t;
    for (std::size_t v = 0; v < 3; ++v) {
      t[v] = scale * Vec3(read_f32_le(p + 12 * v), read_f32_le(p + 12 * v + 4), read_f32_le(p + 12 * v + 8));
      check_finite(t[v], name, k);
    }
    tris.push_back(t);
  }
  return tris;
}

std::vector<Triangle> parse_ascii(const std::string& bytes, const std::string& name, double scale) {
  std::istringstream s(bytes);
  std::string word;
  s >> word;  // "solid"
  std::vector<Triangle> tris;
  Triangle t;
  std::size_t in_loop = 0;  // vertices read in the current loop
  bool loop_open = false;
  while (s >> word) {
    if (word == "outer") {
      if (!(s >> word) || word != "loop")
        throw SettingError(name, "facet " + std::to_string(tris.size()) + ": 'outer' not followed by 'loop'");
      loop_open = true;
      in_loop = 0;
    } else if (word == "vertex") {
      if (!loop_open || in_loop >= 3)
        throw SettingError(name, "facet " + std::to_string(tris.size()) +
                                     ": a 'vertex' outside an 'outer loop' or a fourth vertex");
      double x, y, z;
      if (!(s >> x >> y >> z))
        throw SettingError(name, "facet " + std::to_string(tris.size()) + ": a 'vertex' needs 3 numbers");
      t[in_loop] = scale * Vec3(x, y, z);
      check_finite(t[in_loop], name, tris.size());
      ++in_loop;
    } else if (word == "endloop") {
      if (!loop_open || in_loop != 3)
        throw SettingError(name, "facet " + std::to_string(tris.size()) + ": a loop needs exactly 3 vertices");
      tris.push_back(t);
      loop_open = false;
    } else if (word == "endsolid") {
      break;
    }
    // "facet normal nx ny nz", "endfacet" and the solid's name: nothing to keep.
  }
  if (loop_open) throw SettingError(name, "the file ends inside a facet (truncated?)");
  return tris;
}

}  // namespace

std::vector<Triangle> parse_stl(const std::string& bytes, const std::string& name, double scale) {
  if (!(scale > 0.0) || !std::isfinite(scale)) throw SettingError(name, "STL scale must be > 0");
  if (bytes.empty()) throw SettingError(name, "the STL file is empty");
  std::vector<Triangle> tris;
  bool binary = false;
  if (bytes.size() >= 84) {
    const std::uint32_t n = read_u32_le(bytes.data() + 80);
    binary = bytes.size() == 84 + 50ull * n;
    if (binary) tris = parse_binary(bytes, name, n, scale);
  }
  if (!binary) {
    const auto first = bytes.find_first_not_of(" \t\r\n");
    if (first == std::string::npos || bytes.compare(first, 5, "solid") != 0) {
      std::ostringstream m;
      m << "neither a binary STL (" << bytes.size() << " bytes";
      if (bytes.size() >= 84) m << ", header says " << read_u32_le(bytes.data() + 80) << " triangles";
      m << "; a binary file has 84 + 50 n bytes) nor an ASCII one (starting with 'solid')";
      throw SettingError(name, m.str());
    }
    tris = parse_ascii(bytes.substr(first), name, scale);
  }
  if (tris.empty()) throw SettingError(name, "the STL file holds no triangles");
  return tris;
}

std::vector<Triangle> read_stl(const std::string& path, double scale) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SettingError(path, "cannot open the STL file");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return parse_stl(bytes, path, scale);
}

}  // namespace seedcal
