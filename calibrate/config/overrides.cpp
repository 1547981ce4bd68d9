#include "calibrate/config/overrides.hpp"

#include <sstream>

#include "store/errors.hpp"

namespace seedcal {
namespace {

toml::value parse_value(const std::string& text) {
  try {
    std::istringstream in("v = " + text);
    const toml::value doc = toml::parse(in, "--set");
    return doc.at("v");
  } catch (const std::exception&) {
    return toml::value(text);  // a bare word: a string
  }
}

std::vector<std::string> split(const std::string& key) {
  std::vector<std::string> parts;
  std::string cur;
  for (char c : key) {
    if (c == '.') { parts.push_back(cur); cur.clear(); }
    else cur += c;
  }
  parts.push_back(cur);
  return parts;
}

// Finds an element named `name` in any array of tables of `table`.
toml::value* find_named(toml::value& table, const std::string& name) {
  for (auto& [key, member] : table.as_table()) {
    if (!member.is_array()) continue;
    for (auto& element : member.as_array())
      if (element.is_table() && element.contains("name") && element.at("name").is_string() &&
          element.at("name").as_string().str == name)
        return &element;
  }
  return nullptr;
}

}  // namespace

void apply_overrides(toml::value& root, const std::vector<std::string>& sets) {
  std::vector<std::string> problems;
  for (const std::string& s : sets) {
    const auto eq = s.find('=');
    if (eq == std::string::npos || eq == 0) {
      problems.push_back("--set " + s + ": must be KEY=VALUE, e.g. --set seed_seed.static_friction=0.4");
      continue;
    }
    const std::string key = s.substr(0, eq);
    const auto parts = split(key);
    toml::value* cur = &root;
    bool ok = true;
    for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
      const std::string& p = parts[i];
      if (p.empty() || !cur->is_table()) { ok = false; break; }
      if (cur->contains(p) && cur->at(p).is_table()) {
        cur = &cur->as_table().at(p);
      } else if (toml::value* named = find_named(*cur, p)) {
        cur = named;
      } else if (!cur->contains(p)) {
        cur->as_table()[p] = toml::table{};
        cur = &cur->as_table().at(p);
      } else {
        ok = false;
        break;
      }
    }
    if (!ok || parts.back().empty() || !cur->is_table()) {
      problems.push_back("--set " + s + ": '" + key + "' is not a path to a key of the config");
      continue;
    }
    cur->as_table()[parts.back()] = parse_value(s.substr(eq + 1));
  }
  if (!problems.empty()) throw InputError(problems);
}

}  // namespace seedcal
