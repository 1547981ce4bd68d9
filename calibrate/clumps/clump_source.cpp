#include "calibrate/clumps/clump_source.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "solver/clump/buried_spheres.hpp"

namespace seedcal {

std::string resolve_data_path(const std::string& path, const std::string& config_path) {
  namespace fs = std::filesystem;
  const fs::path p(path);
  if (p.is_absolute()) return path;
  // The config's own directory first: a file that names "clump.txt" means the one beside it, even
  // when the working directory holds another file of that name.
  const fs::path beside = fs::path(config_path).parent_path() / p;
  if (fs::exists(beside)) return beside.string();
  return path;  // relative to the working directory (a path given on the command line)
}

namespace {

// "x y z r" per line, '#' comments.
std::vector<SphereXYZR> read_text_clump(const std::string& path, TomlReader& reader,
                                        const std::string& key) {
  std::ifstream in(path);
  std::vector<SphereXYZR> out;
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    ++n;
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    std::istringstream ls(line);
    double x, y, z, r;
    if (!(ls >> x)) continue;
    if (!(ls >> y >> z >> r) || !(r > 0.0)) {
      reader.error(key, "= \"" + path + "\": line " + std::to_string(n) +
                            " must be 'x y z r' in m with r > 0");
      return {};
    }
    out.push_back({Vec3(x, y, z), r});
  }
  return out;
}

std::string sphere_text(const std::vector<SphereXYZR>& s, std::size_t i) {
  std::ostringstream t;
  t.precision(4);
  const Vec3& c = s[i].centre_m;
  t << "sphere " << i + 1 << " (r = " << s[i].radius_m << " m at " << c.x() << ", " << c.y() << ", " << c.z()
    << " m)";
  return t.str();
}

}  // namespace

void warn_buried_spheres(const std::vector<SphereXYZR>& s, const std::string& source, TomlReader& reader,
                         const std::string& key) {
  const std::vector<BuriedSphere> buried = buried_spheres(s, 0.01);
  if (buried.empty()) return;
  std::ostringstream m;
  m << source << buried.size() << " of " << s.size()
    << " spheres lie inside another sphere of the clump (reaching less than 1 % of their radius out "
       "of it): ";
  const std::size_t shown = std::min<std::size_t>(buried.size(), 4);
  for (std::size_t k = 0; k < shown; ++k)
    m << (k ? "; " : "") << sphere_text(s, buried[k].sphere) << " in " << sphere_text(s, buried[k].inside);
  if (shown < buried.size()) m << "; and " << buried.size() - shown << " more";
  m << ". They add no surface, yet the time step follows the smallest sphere: remove them, or rebuild "
       "the clump (seedcal clump build, docs/clumps.md)";
  reader.warn(key, m.str());
}

std::vector<SphereXYZR> load_clump_spheres(const std::string& path, TomlReader& reader,
                                           const std::string& key) {
  std::ifstream probe(path);
  if (!probe) {
    reader.error(key, "= \"" + path + "\": cannot open the clump file");
    return {};
  }
  std::vector<SphereXYZR> out;
  if (path.size() >= 5 && path.substr(path.size() - 5) == ".toml") {
    // Clump file: spheres_m = [[x, y, z, r], ...] in the body frame (see docs/clumps.md).
    toml::value doc;
    try {
      doc = TomlReader::parse_file(path);
    } catch (const InputError& e) {
      reader.error(key, "= \"" + path + "\": " + e.what());
      return {};
    }
    auto diag = std::make_shared<ConfigDiagnostics>();
    diag->file = path;
    TomlReader file(doc, "", diag);
    for (const auto& row : file.number_rows("spheres_m", 4, 1, 100000))
      out.push_back({Vec3(row[0], row[1], row[2]), row[3]});
    for (const auto& s : out)
      if (!(s.radius_m > 0.0)) diag->add(nullptr, "spheres_m", "every radius must be > 0");
    for (const auto& msg : diag->problems) reader.diagnostics().problems.push_back(msg);
  } else {
    out = read_text_clump(path, reader, key);
  }
  if (out.empty()) reader.error(key, "= \"" + path + "\": the clump file holds no spheres");
  warn_buried_spheres(out, "= \"" + path + "\": ", reader, key);
  return out;
}

}  // namespace seedcal
