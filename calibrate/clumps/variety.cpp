#include "calibrate/clumps/variety.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>

#include "calibrate/config/toml_reader.hpp"

namespace seedcal {

EllipsoidSpec Variety::shape() const {
  return {length_m, width_m, thickness_m, hilum_radius_m, hilum_centre};
}

std::string variety_path(const std::string& name_or_path) {
  namespace fs = std::filesystem;
  if (name_or_path.size() > 5 && name_or_path.substr(name_or_path.size() - 5) == ".toml") {
    if (!fs::exists(name_or_path)) throw InputError(name_or_path + ": variety file not found");
    return name_or_path;
  }
  std::vector<std::string> tried;
  const fs::path local = fs::path("data/varieties") / (name_or_path + ".toml");
  tried.push_back(local.string());
  if (fs::exists(local)) return local.string();
  if (const char* dir = std::getenv("SEEDCAL_DATA_DIR")) {
    const fs::path p = fs::path(dir) / "varieties" / (name_or_path + ".toml");
    tried.push_back(p.string());
    if (fs::exists(p)) return p.string();
  }
  std::vector<std::string> names;
  if (fs::is_directory("data/varieties"))
    for (const auto& e : fs::directory_iterator("data/varieties"))
      if (e.path().extension() == ".toml") names.push_back(e.path().stem().string());
  std::sort(names.begin(), names.end());
  std::string avail;
  for (const auto& n : names) avail += (avail.empty() ? "" : ", ") + n;
  std::string msg = "--variety " + name_or_path + ": no such variety (looked for";
  for (const auto& t : tried) msg += " " + t;
  msg += ")";
  if (!avail.empty()) msg += "; available: " + avail;
  throw InputError(msg);
}

Variety read_variety(const std::string& name_or_path) {
  Variety v;
  v.file = variety_path(name_or_path);
  const toml::value doc = TomlReader::parse_file(v.file);
  auto diag = std::make_shared<ConfigDiagnostics>();
  diag->file = v.file;
  TomlReader r(doc, "", diag);
  const Range pos = Range::positive();
  v.name = r.string("name");
  v.density_kg_m3 = r.number("density_kg_m3", Range::closed(100, 5000));
  v.moisture_fraction = r.number("moisture_fraction", Range::closed(0, 1));
  v.thousand_seed_mass_kg = r.number("thousand_seed_mass_kg", pos);
  v.best_compromise_spheres = static_cast<int>(r.integer("best_compromise_spheres", 1, 100000, 0));
  if (auto s = r.table("clump_shape")) {
    v.hilum_radius_m = s->number("hilum_radius_m", Range::closed(0, 0.1), 0.0);
    v.hilum_centre = s->number("hilum_centre", Range::closed(0, 1), 0.85);
    s->check_unknown_keys();
  }
  if (auto d = r.table("dimensions")) {
    const Range mm = Range::left_open(0, 0.5);  // a seed up to 0.5 m: catches mm given as m
    v.length_m = d->number("length_m", mm);
    v.length_sd_m = d->number("length_sd_m", Range::non_negative());
    v.width_m = d->number("width_m", mm);
    v.width_sd_m = d->number("width_sd_m", Range::non_negative());
    v.thickness_m = d->number("thickness_m", mm);
    v.thickness_sd_m = d->number("thickness_sd_m", Range::non_negative());
    d->check_unknown_keys();
  } else {
    r.error("dimensions", "is required (length_m, width_m, thickness_m and their sd)");
  }
  if (auto w = r.table("width_distribution")) {
    v.width_mean_m = w->number("mean_m", Range::left_open(0, 0.5));
    v.width_dist_sd_m = w->number("sd_m", Range::non_negative());
    w->check_unknown_keys();
  } else {
    v.width_mean_m = v.width_m;
    v.width_dist_sd_m = v.width_sd_m;
  }
  if (auto s = r.table("soaking")) {
    v.soak_hours = s->numbers("hours", Range::positive(), 1, 100);
    for (const auto& row : s->number_rows("before_m", 3, 1, 100)) v.soak_before_m.emplace_back(row[0], row[1], row[2]);
    for (const auto& row : s->number_rows("after_m", 3, 1, 100)) v.soak_after_m.emplace_back(row[0], row[1], row[2]);
    if (v.soak_before_m.size() != v.soak_hours.size() || v.soak_after_m.size() != v.soak_hours.size())
      s->error("hours", "needs one before_m and one after_m row per entry");
    for (std::size_t i = 1; i < v.soak_hours.size(); ++i)
      if (!(v.soak_hours[i] > v.soak_hours[i - 1])) s->error("hours", "must increase");
    s->check_unknown_keys();
  }
  if (auto m = r.table("moisture_modulus")) {
    v.mc_moisture_fraction = m->numbers("moisture_fraction", Range::closed(0, 1), 2, 100);
    v.mc_youngs_modulus_pa = m->numbers("youngs_modulus_pa", Range::positive(), 2, 100);
    if (v.mc_moisture_fraction.size() != v.mc_youngs_modulus_pa.size())
      m->error("youngs_modulus_pa", "needs one value per moisture_fraction");
    v.mc_flag = m->string("flag", "");
    m->check_unknown_keys();
  }
  for (auto& c : r.table_array("clump_volume")) {
    PaperClump p;
    p.filling = c.choice("filling", {"manual", "automatic"});
    p.spheres = static_cast<int>(c.integer("spheres", 1, 100000));
    p.volume_m3 = c.number("volume_m3", Range::open(0, 1e-3));
    p.ratio = c.number("ratio", Range::open(0, 10));
    p.flag = c.string("ratio_flag", "");
    c.check_unknown_keys();
    v.paper_clumps.push_back(p);
  }
  auto numbers_of = [&](const std::string& table, std::map<std::string, double>& out) {
    auto t = r.table(table);
    if (!t) return;
    const toml::value& tv = doc.at(table);
    for (const auto& [k, val] : tv.as_table()) {
      if (val.is_string()) v.flags[table + "." + k] = t->string(k);
      else out[k] = t->number(k, Range{});
    }
    t->check_unknown_keys();
  };
  numbers_of("simulation", v.simulation);
  numbers_of("targets", v.targets);
  if (auto mc = r.table("material_contact")) {
    for (const std::string& material : mc->keys()) {
      auto c = mc->table(material);
      if (!c) continue;
      auto& values = v.material_contact[material];
      // The ranges of an [[interaction]] (calibrate/config/physics_config.cpp).
      values["restitution"] = c->number("restitution", Range::left_open(0.0, 1.0));
      values["static_friction"] = c->number("static_friction", Range::closed(0.0, 10.0));
      values["rolling_friction"] = c->number("rolling_friction", Range::closed(0.0, 10.0), 0.0);
      c->check_unknown_keys();
    }
  }
  if (auto m = r.table("models")) {
    namespace fs = std::filesystem;
    for (const std::string& name : m->keys()) {
      const std::string file = m->string(name);
      // Checked when a scene uses the model (variety_model_file): `seedcal clump build --variety`
      // reads the variety before its models are built.
      const fs::path path = fs::path(v.file).parent_path() / file;
      v.models[name] = fs::path(file).is_absolute() ? file : path.lexically_normal().string();
    }
    m->check_unknown_keys();
  }
  v.default_model = r.string("default_model", "");
  if (!v.default_model.empty() && !v.models.count(v.default_model))
    r.error("default_model", "= \"" + v.default_model + "\": not one of [models]");
  r.check_unknown_keys();
  diag->throw_if_any();
  return v;
}

std::string variety_model_file(const Variety& v, const std::string& name) {
  const auto it = v.models.find(name);
  if (it != v.models.end()) {
    if (!std::filesystem::exists(it->second))
      throw InputError(v.file + ": models." + name + " = \"" + it->second + "\": clump file not found (a path "
                       "relative to the variety file; `seedcal clump build --variety " + v.file + " ... --out FILE` "
                       "writes one)");
    return it->second;
  }
  std::string names;
  for (const auto& [n, _] : v.models) names += (names.empty() ? "" : ", ") + n;
  throw InputError(v.file + ": [models] has no model \"" + name + "\" (it has: " +
                   (names.empty() ? "none" : names) + ")");
}

}  // namespace seedcal
