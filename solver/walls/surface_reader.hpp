#pragma once
// Triangle surfaces as scanners and CAD programs write them: STL (stl_reader.hpp), PLY and
// Wavefront OBJ. Polygons of more than three vertices are split into a fan of triangles from their
// first vertex (scanners write triangles; a CAD export's quads are planar and convex). Every failure
// throws SettingError whose key is the file's name and whose message says what is wrong and where.
//
// PLY (Turk, "The PLY polygon file format", 1994; the format as Paul Bourke's page documents it):
// a header ("ply", "format ascii|binary_little_endian|binary_big_endian 1.0", "element NAME N",
// "property TYPE NAME" or "property list COUNT_TYPE ITEM_TYPE NAME", "end_header") and the
// elements' data in header order. The "vertex" element's x, y, z and the "face" element's
// vertex_indices (or vertex_index) list are read; every other element and property is skipped.
//
// OBJ (Wavefront Technologies, "Appendix B1: Object Files (.obj)"): "v x y z [w]" vertices and
// "f i j k ..." faces whose entries are "i", "i/t", "i//n" or "i/t/n", 1-based, negative counting
// back from the last vertex read; every other statement (vt, vn, g, o, s, usemtl, mtllib, l, p) is
// skipped.
#include <string>
#include <vector>

#include "solver/walls/stl_reader.hpp"

namespace seedcal {

// Each vertex is multiplied by `scale` (1e-3 for a file in millimetres); `name` is used in messages.
std::vector<Triangle> parse_ply(const std::string& bytes, const std::string& name, double scale = 1.0);
std::vector<Triangle> parse_obj(const std::string& bytes, const std::string& name, double scale = 1.0);

// The surface formats read_surface knows, by file extension (lower case, with the dot).
const std::vector<std::string>& surface_extensions();

// Reads `path` by its extension (.stl, .ply or .obj, any case).
std::vector<Triangle> read_surface(const std::string& path, double scale = 1.0);

}  // namespace seedcal
