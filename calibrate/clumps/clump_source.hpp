#pragma once
// Where scenes get a clump's spheres from: a clump file (TOML written by `seedcal clump build`, or
// a plain "x y z r" text file such as data/bench/clump9.txt), with paths relative to the config
// that names them or, failing that, to the working directory.
#include <string>
#include <vector>

#include "calibrate/config/toml_reader.hpp"
#include "solver/clump/mass_properties.hpp"

namespace seedcal {

// A path as written in a config: absolute, relative to the config file's directory, or relative to
// the working directory (tried in that order; the last for a path given on the command line).
std::string resolve_data_path(const std::string& path, const std::string& config_path);

// Spheres of a clump file in its own frame; problems are reported on `reader` under `key`, and a
// warning names any sphere wholly inside another (warn_buried_spheres).
std::vector<SphereXYZR> load_clump_spheres(const std::string& path, TomlReader& reader,
                                           const std::string& key);

// A sphere wholly inside another of the clump (reaching less than 1 % of its radius out of it) adds
// no surface, yet sets the time step when it is the smallest (solver/clump/buried_spheres.hpp):
// allowed, but said as a warning on `reader` under `key`, the message starting with `source`.
void warn_buried_spheres(const std::vector<SphereXYZR>& spheres, const std::string& source, TomlReader& reader,
                         const std::string& key);

}  // namespace seedcal
