#pragma once
// STL reader (binary and ASCII), the solver's one piece of file input. A file is binary when its
// size is exactly 84 + 50 n bytes, n being the little-endian uint32 at byte 80 (the only reliable
// test: binary files may also begin with "solid"); otherwise it must be ASCII, starting with
// "solid" and holding "facet ... outer loop vertex x y z (x3) endloop endfacet" blocks.
// Every failure throws SettingError whose key is the file's path and whose message says what is
// wrong (cannot open, empty, truncated, no triangles, a malformed number, a non-finite vertex).
#include <array>
#include <string>
#include <vector>

#include "solver/core/vec.hpp"

namespace seedcal {

using Triangle = std::array<Vec3, 3>;

// Triangles of the file, each vertex multiplied by `scale` (e.g. 1e-3 for a file in mm). The
// facet normals stored in the file are ignored: they are often wrong or zero, and the walls are
// two-sided.
std::vector<Triangle> read_stl(const std::string& path, double scale = 1.0);

// The same from the file's bytes; `name` is used in messages.
std::vector<Triangle> parse_stl(const std::string& bytes, const std::string& name, double scale = 1.0);

}  // namespace seedcal
