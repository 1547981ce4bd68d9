#include "solver/walls/surface_reader.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>

#include "solver/core/errors.hpp"

namespace seedcal {
namespace {

// A whole token as a finite double, or false.
bool to_double(const std::string& token, double& out) {
  if (token.empty()) return false;
  char* end = nullptr;
  errno = 0;
  out = std::strtod(token.c_str(), &end);
  return end == token.c_str() + token.size() && errno == 0 && std::isfinite(out);
}

// A whole token as an integer (a PLY count or index written as "3" or "3.0"), or false.
bool to_integer(const std::string& token, long long& out) {
  double d = 0.0;
  if (!to_double(token, d) || d != std::floor(d) || std::abs(d) > 9.0e15) return false;
  out = static_cast<long long>(d);
  return true;
}

void check_scale(double scale, const std::string& name) {
  if (!(scale > 0.0) || !std::isfinite(scale)) throw SettingError(name, "the surface's scale must be > 0");
}

// Faces (vertex index lists, already 0-based and checked) as a fan of triangles each.
std::vector<Triangle> triangulate(const std::vector<Vec3>& v, const std::vector<std::vector<std::size_t>>& faces,
                                  const std::string& name) {
  std::vector<Triangle> tris;
  for (const auto& f : faces)
    for (std::size_t k = 1; k + 1 < f.size(); ++k) tris.push_back({v[f[0]], v[f[k]], v[f[k + 1]]});
  if (tris.empty()) throw SettingError(name, "the surface holds no triangles");
  return tris;
}

// ------------------------------------------------------------------------------------------------
// PLY

enum class PlyFormat { ascii, little_endian, big_endian };

struct PlyType {
  int bytes = 0;
  bool floating = false, is_signed = false;
};

bool ply_type(const std::string& t, PlyType& out) {
  static const std::pair<const char*, PlyType> kTypes[] = {
      {"char", {1, false, true}},    {"int8", {1, false, true}},    {"uchar", {1, false, false}},
      {"uint8", {1, false, false}},  {"short", {2, false, true}},   {"int16", {2, false, true}},
      {"ushort", {2, false, false}}, {"uint16", {2, false, false}}, {"int", {4, false, true}},
      {"int32", {4, false, true}},   {"uint", {4, false, false}},   {"uint32", {4, false, false}},
      {"float", {4, true, true}},    {"float32", {4, true, true}},  {"double", {8, true, true}},
      {"float64", {8, true, true}}};
  for (const auto& [n, type] : kTypes)
    if (t == n) {
      out = type;
      return true;
    }
  return false;
}

struct PlyProperty {
  std::string name;
  PlyType type;
  bool list = false;
  PlyType count_type;
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

// The data after the header: numbers one at a time, as text or binary.
class PlyData {
 public:
  PlyData(const std::string& bytes, std::size_t at, PlyFormat f, const std::string& name)
      : bytes_(bytes), at_(at), format_(f), name_(name) {}

  double read(const PlyType& t, const std::string& what) {
    if (format_ == PlyFormat::ascii) {
      const std::string token = next_token();
      double d = 0.0;
      if (token.empty()) throw SettingError(name_, "the data end before " + what + " (truncated?)");
      if (!to_double(token, d)) throw SettingError(name_, what + ": '" + token.substr(0, 40) + "' is not a number");
      return d;
    }
    if (bytes_.size() - at_ < static_cast<std::size_t>(t.bytes))
      throw SettingError(name_, "the data end before " + what + " (truncated?)");
    const auto* p = reinterpret_cast<const unsigned char*>(bytes_.data() + at_);
    at_ += static_cast<std::size_t>(t.bytes);
    // The value's bits, most significant byte first: the last in a little-endian file.
    std::uint64_t u = 0;
    for (int k = 0; k < t.bytes; ++k) u = (u << 8) | p[format_ == PlyFormat::big_endian ? k : t.bytes - 1 - k];
    double d = 0.0;
    if (t.floating && t.bytes == 4) {
      float f = 0.0f;
      const auto u32 = static_cast<std::uint32_t>(u);
      std::memcpy(&f, &u32, sizeof f);
      d = f;
    } else if (t.floating) {
      std::memcpy(&d, &u, sizeof d);
    } else if (t.is_signed) {
      const int bits = 8 * t.bytes;
      const auto s = static_cast<std::int64_t>(u << (64 - bits)) >> (64 - bits);  // sign-extend
      d = static_cast<double>(s);
    } else {
      d = static_cast<double>(u);
    }
    if (!std::isfinite(d)) throw SettingError(name_, what + " is not finite");
    return d;
  }

 private:
  std::string next_token() {
    while (at_ < bytes_.size() && std::isspace(static_cast<unsigned char>(bytes_[at_]))) ++at_;
    const std::size_t start = at_;
    while (at_ < bytes_.size() && !std::isspace(static_cast<unsigned char>(bytes_[at_]))) ++at_;
    return bytes_.substr(start, at_ - start);
  }

  const std::string& bytes_;
  std::size_t at_;
  PlyFormat format_;
  const std::string& name_;
};

}  // namespace

std::vector<Triangle> parse_ply(const std::string& bytes, const std::string& name, double scale) {
  check_scale(scale, name);
  if (bytes.compare(0, 3, "ply") != 0) throw SettingError(name, "not a PLY file (it must start with 'ply')");
  // The header, line by line ("\n" or "\r\n").
  std::size_t at = 0;
  std::vector<PlyElement> elements;
  PlyFormat format = PlyFormat::ascii;
  bool have_format = false, ended = false;
  for (int line_no = 1; at < bytes.size(); ++line_no) {
    std::size_t eol = bytes.find('\n', at);
    if (eol == std::string::npos) eol = bytes.size();
    std::istringstream line(bytes.substr(at, eol - at));
    at = std::min(bytes.size(), eol + 1);
    const std::string where = "header line " + std::to_string(line_no);
    std::string word;
    if (!(line >> word) || word == "comment" || word == "obj_info") continue;
    if (line_no == 1) {
      if (word != "ply") throw SettingError(name, "not a PLY file (it must start with 'ply')");
      continue;
    }
    if (word == "end_header") {
      ended = true;
      break;
    }
    if (word == "format") {
      std::string f;
      line >> f;
      if (f == "ascii") format = PlyFormat::ascii;
      else if (f == "binary_little_endian") format = PlyFormat::little_endian;
      else if (f == "binary_big_endian") format = PlyFormat::big_endian;
      else throw SettingError(name, where + ": format '" + f + "': allowed ascii, binary_little_endian, binary_big_endian");
      have_format = true;
    } else if (word == "element") {
      PlyElement e;
      std::string count;
      long long n = 0;
      if (!(line >> e.name >> count) || !to_integer(count, n) || n < 0)
        throw SettingError(name, where + ": 'element NAME COUNT' with a count >= 0");
      e.count = static_cast<std::uint64_t>(n);
      elements.push_back(std::move(e));
    } else if (word == "property") {
      if (elements.empty()) throw SettingError(name, where + ": a property before any element");
      PlyProperty p;
      std::string t;
      line >> t;
      if (t == "list") {
        std::string ct, it;
        line >> ct >> it >> p.name;
        if (!ply_type(ct, p.count_type) || p.count_type.floating || !ply_type(it, p.type))
          throw SettingError(name, where + ": 'property list COUNT_TYPE ITEM_TYPE NAME' with an integer count type");
        p.list = true;
      } else {
        line >> p.name;
        if (!ply_type(t, p.type)) throw SettingError(name, where + ": unknown property type '" + t + "'");
      }
      if (p.name.empty()) throw SettingError(name, where + ": the property has no name");
      elements.back().properties.push_back(p);
    } else {
      throw SettingError(name, where + ": unknown header keyword '" + word.substr(0, 40) + "'");
    }
  }
  if (!ended) throw SettingError(name, "the header has no 'end_header' line");
  if (!have_format) throw SettingError(name, "the header has no 'format' line");

  PlyData data(bytes, at, format, name);
  std::vector<Vec3> vertices;
  std::vector<std::vector<long long>> raw_faces;
  bool have_vertices = false, have_faces = false;
  for (const PlyElement& e : elements) {
    if (e.properties.empty()) continue;  // nothing to read
    const bool is_vertex = e.name == "vertex", is_face = e.name == "face";
    int ix = -1, iy = -1, iz = -1, iface = -1;
    for (std::size_t k = 0; k < e.properties.size(); ++k) {
      const PlyProperty& p = e.properties[k];
      if (is_vertex && !p.list && p.name == "x") ix = static_cast<int>(k);
      if (is_vertex && !p.list && p.name == "y") iy = static_cast<int>(k);
      if (is_vertex && !p.list && p.name == "z") iz = static_cast<int>(k);
      if (is_face && p.list && (p.name == "vertex_indices" || p.name == "vertex_index")) iface = static_cast<int>(k);
    }
    if (is_vertex && (ix < 0 || iy < 0 || iz < 0))
      throw SettingError(name, "the vertex element needs scalar properties x, y and z");
    if (is_face && iface < 0) throw SettingError(name, "the face element needs a list property vertex_indices");
    have_vertices |= is_vertex;
    have_faces |= is_face;
    for (std::uint64_t i = 0; i < e.count; ++i) {
      const std::string what = e.name + " " + std::to_string(i);
      Vec3 v = Vec3::Zero();
      for (std::size_t k = 0; k < e.properties.size(); ++k) {
        const PlyProperty& p = e.properties[k];
        if (!p.list) {
          const double x = data.read(p.type, what);
          if (static_cast<int>(k) == ix) v.x() = x;
          if (static_cast<int>(k) == iy) v.y() = x;
          if (static_cast<int>(k) == iz) v.z() = x;
          continue;
        }
        const double n = data.read(p.count_type, what + " list count");
        if (n < 0.0 || n != std::floor(n)) throw SettingError(name, what + ": a list count must be a whole number >= 0");
        std::vector<long long> items;
        for (double j = 0; j < n; ++j) {
          const double x = data.read(p.type, what + " list item");
          if (static_cast<int>(k) == iface) {
            if (x != std::floor(x)) throw SettingError(name, what + ": a vertex index must be a whole number");
            items.push_back(static_cast<long long>(std::clamp(x, -1.0, 9.0e15)));
          }
        }
        if (static_cast<int>(k) == iface) {
          if (items.size() < 3) throw SettingError(name, what + ": a face needs at least 3 vertices");
          raw_faces.push_back(std::move(items));
        }
      }
      if (is_vertex) vertices.push_back(scale * v);
    }
  }
  if (!have_vertices) throw SettingError(name, "the file has no vertex element");
  if (!have_faces) throw SettingError(name, "the file has no face element (a point cloud is not a surface)");
  std::vector<std::vector<std::size_t>> faces;
  faces.reserve(raw_faces.size());
  for (std::size_t f = 0; f < raw_faces.size(); ++f) {
    std::vector<std::size_t> idx;
    for (const long long i : raw_faces[f]) {
      if (i < 0 || static_cast<unsigned long long>(i) >= vertices.size())
        throw SettingError(name, "face " + std::to_string(f) + ": vertex index " + std::to_string(i) +
                                     " outside 0 .. " + std::to_string(vertices.size()) + " - 1");
      idx.push_back(static_cast<std::size_t>(i));
    }
    faces.push_back(std::move(idx));
  }
  for (std::size_t i = 0; i < vertices.size(); ++i)
    if (!vertices[i].allFinite()) throw SettingError(name, "vertex " + std::to_string(i) + " is not finite after scaling");
  return triangulate(vertices, faces, name);
}

std::vector<Triangle> parse_obj(const std::string& bytes, const std::string& name, double scale) {
  check_scale(scale, name);
  std::vector<Vec3> vertices;
  std::vector<std::vector<long long>> raw_faces;  // 0-based, unchecked
  std::vector<int> face_line;
  std::size_t at = 0;
  for (int line_no = 1; at < bytes.size(); ++line_no) {
    std::size_t eol = bytes.find('\n', at);
    if (eol == std::string::npos) eol = bytes.size();
    std::istringstream line(bytes.substr(at, eol - at));
    at = std::min(bytes.size(), eol + 1);
    const std::string where = "line " + std::to_string(line_no);
    std::string word;
    if (!(line >> word) || word[0] == '#') continue;
    if (word == "v") {
      std::string t[3];
      double x[3];
      for (int k = 0; k < 3; ++k)
        if (!(line >> t[k]) || !to_double(t[k], x[k]))
          throw SettingError(name, where + ": 'v x y z' needs three finite numbers");
      const Vec3 v = scale * Vec3(x[0], x[1], x[2]);
      if (!v.allFinite()) throw SettingError(name, where + ": the vertex is not finite after scaling");
      vertices.push_back(v);
    } else if (word == "f") {
      std::vector<long long> f;
      std::string entry;
      while (line >> entry) {
        long long i = 0;
        if (!to_integer(entry.substr(0, entry.find('/')), i) || i == 0)
          throw SettingError(name, where + ": face entry '" + entry.substr(0, 40) +
                                       "' is not a vertex index (1-based, or negative counting back)");
        // Negative indices count back from the last vertex read so far.
        f.push_back(i > 0 ? i - 1 : static_cast<long long>(vertices.size()) + i);
      }
      if (f.size() < 3) throw SettingError(name, where + ": a face needs at least 3 vertices");
      raw_faces.push_back(std::move(f));
      face_line.push_back(line_no);
    }
    // vt, vn, vp, g, o, s, usemtl, mtllib, l, p: nothing a solid's surface needs.
  }
  if (vertices.empty()) throw SettingError(name, "the file has no vertices ('v x y z' lines)");
  if (raw_faces.empty()) throw SettingError(name, "the file has no faces ('f i j k' lines)");
  std::vector<std::vector<std::size_t>> faces;
  faces.reserve(raw_faces.size());
  for (std::size_t k = 0; k < raw_faces.size(); ++k) {
    std::vector<std::size_t> idx;
    for (const long long i : raw_faces[k]) {
      if (i < 0 || static_cast<unsigned long long>(i) >= vertices.size())
        throw SettingError(name, "line " + std::to_string(face_line[k]) + ": the face names vertex " +
                                     std::to_string(i + 1) + " of " + std::to_string(vertices.size()));
      idx.push_back(static_cast<std::size_t>(i));
    }
    faces.push_back(std::move(idx));
  }
  return triangulate(vertices, faces, name);
}

const std::vector<std::string>& surface_extensions() {
  static const std::vector<std::string> kExtensions = {".stl", ".ply", ".obj"};
  return kExtensions;
}

std::vector<Triangle> read_surface(const std::string& path, double scale) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".stl") return read_stl(path, scale);
  if (ext != ".ply" && ext != ".obj")
    throw SettingError(path, "unknown surface format '" + ext + "' (allowed: .stl, .ply, .obj)");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SettingError(path, "cannot open the surface file");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.empty()) throw SettingError(path, "the surface file is empty");
  return ext == ".ply" ? parse_ply(bytes, path, scale) : parse_obj(bytes, path, scale);
}

}  // namespace seedcal
