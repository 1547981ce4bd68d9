#include "calibrate/config/variety_scene.hpp"

#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>

#include "calibrate/clumps/clump_source.hpp"
#include "calibrate/clumps/variety.hpp"
#include "store/errors.hpp"

namespace seedcal {
namespace {

constexpr const char* kSeedMaterial = "seed";
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string variety_number_text(double v) {
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}

std::string scene_value_text(const toml::value& v) {
  if (v.is_floating()) return variety_number_text(v.as_floating());
  if (v.is_integer()) return std::to_string(v.as_integer());
  return toml::format(v);
}

bool same_number(const toml::value& v, double x) {
  const double y = v.is_floating() ? v.as_floating() : v.is_integer() ? static_cast<double>(v.as_integer()) : kNaN;
  return std::abs(y - x) <= 1e-12 * std::max(1.0, std::abs(x));
}

toml::value& subtable(toml::value& t, const std::string& key, const std::string& scene_path) {
  if (!t.contains(key)) t.as_table()[key] = toml::table{};
  toml::value& sub = t.as_table().at(key);
  if (!sub.is_table()) throw InputError(scene_path + ": " + key + " = " + toml::format(sub) + ": must be a table");
  return sub;
}

// Sets `table.key` to `value` unless the scene gives it; records what it did under `path`.
void supply(toml::value& table, const std::string& key, double value, const std::string& path, VarietyDefaults& out) {
  if (!table.contains(key)) {
    table.as_table()[key] = value;
    out.filled.push_back(path);
  } else if (same_number(table.at(key), value)) {
    out.repeated.push_back(path);
  } else {
    out.replaced.push_back(path + " = " + scene_value_text(table.at(key)) + " (scene file) replaces the variety's " +
                           variety_number_text(value));
  }
}

// The [[interaction]] between the seed and `material` (by its name seed_<material>, or by its
// `between`), appended when the scene has none.
toml::value& interaction(toml::value& doc, const std::string& material) {
  const std::string name = std::string(kSeedMaterial) + "_" + material;
  if (!doc.contains("interaction")) doc.as_table()["interaction"] = toml::array{};
  toml::value& list = doc.as_table().at("interaction");
  if (list.is_array()) {
    for (toml::value& x : list.as_array()) {
      if (!x.is_table()) continue;
      if (x.contains("name") && x.at("name").is_string() && x.at("name").as_string().str == name) return x;
      if (x.contains("between") && x.at("between").is_array() && x.at("between").as_array().size() == 2) {
        const auto& b = x.at("between").as_array();
        auto is = [](const toml::value& v, const std::string& s) { return v.is_string() && v.as_string().str == s; };
        if ((is(b[0], kSeedMaterial) && is(b[1], material)) || (is(b[0], material) && is(b[1], kSeedMaterial)))
          return x;
      }
    }
    list.as_array().push_back(toml::table{{"name", name}, {"between", toml::array{kSeedMaterial, material}}});
    return list.as_array().back();
  }
  throw InputError("interaction: must be an array of tables ([[interaction]])");
}

}  // namespace

std::string scene_variety_file(const toml::value& doc, const std::string& scene_path) {
  if (!doc.is_table() || !doc.contains("variety")) return "";
  const toml::value& v = doc.at("variety");
  if (!v.is_string()) throw InputError(scene_path + ": variety = " + toml::format(v) + ": must be a string (a variety file or name)");
  const std::string ref = v.as_string().str;
  const bool is_file = ref.size() > 5 && ref.substr(ref.size() - 5) == ".toml";
  const std::string where = scene_path + ": variety = \"" + ref + "\": ";
  if (is_file) {
    const std::string file = resolve_data_path(ref, scene_path);
    if (!std::filesystem::exists(file))
      throw InputError(where + "no such variety file (looked beside the file that names it, " +
                       (std::filesystem::path(scene_path).parent_path() / ref).lexically_normal().string() +
                       ", and in the working directory)");
    return std::filesystem::path(file).lexically_normal().string();
  }
  try {
    return std::filesystem::path(variety_path(ref)).lexically_normal().string();
  } catch (const InputError& e) {
    const std::string m = e.problems().front();
    const auto colon = m.find(": ");
    throw InputError(where + (colon == std::string::npos ? m : m.substr(colon + 2)));
  }
}

VarietyDefaults apply_variety(toml::value& doc, const std::string& scene_path) {
  VarietyDefaults out;
  out.variety_file = scene_variety_file(doc, scene_path);
  if (out.variety_file.empty()) return out;
  const Variety v = read_variety(out.variety_file);
  std::vector<std::string> missing;
  auto value = [&](const std::map<std::string, double>& from, const std::string& key, const std::string& where) {
    const auto it = from.find(key);
    if (it != from.end()) return it->second;
    missing.push_back(where + " " + key);
    return kNaN;
  };
  toml::value& seed = subtable(subtable(doc, "materials", scene_path), kSeedMaterial, scene_path);
  for (const char* key : {"density_kg_m3", "youngs_modulus_pa", "poisson_ratio"}) {
    const bool in_scene = seed.contains(key);
    double x = value(v.simulation, key, "[simulation]");
    if (std::string(key) == "density_kg_m3" && std::isnan(x) && v.density_kg_m3 > 0.0) {
      missing.pop_back();  // the variety's measured density stands in for Table 6's
      x = v.density_kg_m3;
    }
    if (!std::isnan(x)) supply(seed, key, x, std::string("materials.seed.") + key, out);
    else if (in_scene) missing.pop_back();  // the scene gives it: nothing is missing
  }
  auto contact = [&](const std::string& material, const std::map<std::string, double>& values, const std::string& where) {
    toml::value& x = interaction(doc, material);
    const std::string name = x.contains("name") && x.at("name").is_string() ? x.at("name").as_string().str
                                                                          : std::string(kSeedMaterial) + "_" + material;
    for (const char* key : {"restitution", "static_friction", "rolling_friction"}) {
      const double val = value(values, key, where);
      if (!std::isnan(val)) supply(x, key, val, name + "." + key, out);
      else if (x.contains(key)) missing.pop_back();
    }
  };
  contact(kSeedMaterial, v.simulation, "[simulation]");
  for (const auto& [material, _] : doc.at("materials").as_table())
      if (material != kSeedMaterial && v.material_contact.count(material))
        contact(material, v.material_contact.at(material), "[material_contact." + material + "]");
  toml::value& particle = subtable(doc, "particle", scene_path);
  {
    if (!particle.contains("material")) {
      particle.as_table()["material"] = kSeedMaterial;
      out.filled.push_back("particle.material");
    }
    if (v.width_mean_m > 0.0) supply(particle, "scale_sd", v.width_dist_sd_m / v.width_mean_m, "particle.scale_sd", out);
    if (particle.contains("clump_file") && particle.at("clump_file").is_string()) {
      const std::string file = std::filesystem::weakly_canonical(
          resolve_data_path(particle.at("clump_file").as_string().str, scene_path)).string();
      for (const auto& [name, model] : v.models)
        if (std::filesystem::weakly_canonical(model).string() == file)
          out.repeated.push_back("particle.clump_file (the variety's model \"" + name + "\")");
    }
  }
  // A rig key that is a measurement of the seed: the drum's seed mass is its fill x volume x the
  // seeds' measured bulk density ([targets] bulk_density_kg_m3), in each rig table the scene has.
  const auto bulk = v.targets.find("bulk_density_kg_m3");
  if (bulk != v.targets.end() && doc.contains("kind") && doc.at("kind").is_string() &&
      doc.at("kind").as_string().str == "drum" && doc.contains("drum") && doc.at("drum").is_table()) {
    for (auto& [fidelity, rig] : doc.as_table().at("drum").as_table())
      if (rig.is_table()) supply(rig, "bulk_density_kg_m3", bulk->second, "drum." + fidelity + ".bulk_density_kg_m3", out);
  }
  if (!missing.empty()) {
    std::vector<std::string> problems;
    for (const std::string& m : missing)
      problems.push_back(scene_path + ": names the variety " + out.variety_file + ", which gives no " + m +
                         ", and the scene file does not give it either");
    throw InputError(problems);
  }
  return out;
}

std::string scene_clump_file(const toml::value& doc, const std::string& scene_path) {
  if (!doc.is_table() || !doc.contains("particle") || !doc.at("particle").is_table()) return "";
  const toml::value& p = doc.at("particle");
  if (p.contains("clump_file") && p.at("clump_file").is_string())
    return resolve_data_path(p.at("clump_file").as_string().str, scene_path);
  if (p.contains("spheres_m")) return "";
  const std::string variety = scene_variety_file(doc, scene_path);
  if (variety.empty()) return "";
  const Variety v = read_variety(variety);
  const std::string model = p.contains("model") && p.at("model").is_string() ? p.at("model").as_string().str : v.default_model;
  if (model.empty()) return "";
  return variety_model_file(v, model);
}

}  // namespace seedcal
