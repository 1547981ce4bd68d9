#pragma once
// `--set key=value` overrides applied to a parsed TOML document before it is read.
//
// The key is a dotted TOML path (`contact.model`, `drum.speed_rpm`). A path segment that is not a
// key of the current table may name an element of one of its arrays of tables by that element's
// `name` (so `glass_glass.restitution=0.9` reaches the [[interaction]] named "glass_glass"). The
// value is read as a TOML value (`0.4`, `true`, `[1, 2, 3]`, `"text"`); a bare word that is not
// valid TOML is taken as a string (`fidelity=quick`).
#include <string>
#include <vector>

#include <toml.hpp>

namespace seedcal {

// Applies each "key=value"; throws InputError naming the override on a malformed one.
void apply_overrides(toml::value& root, const std::vector<std::string>& sets);

}  // namespace seedcal
