#include "calibrate/config/physics_config.hpp"

#include <set>

namespace seedcal {

std::uint16_t PhysicsConfig::material(TomlReader& reader, const std::string& key,
                                      const std::string& name) const {
  const auto it = material_index.find(name);
  if (it != material_index.end()) return it->second;
  std::vector<std::string> names;
  for (const auto& [n, _] : material_index) names.push_back(n);
  std::string msg = "= \"" + name + "\": no such material (defined: ";
  for (std::size_t i = 0; i < names.size(); ++i) msg += (i ? ", " : "") + names[i];
  msg += ")";
  const std::string hint = did_you_mean(name, names);
  if (!hint.empty()) msg += "; did you mean \"" + hint + "\"?";
  reader.error(key, msg);
  return kUnknown;
}

void PhysicsConfig::require_interaction(TomlReader& reader, const std::string& key, std::uint16_t a,
                                        std::uint16_t b, const std::string& how) const {
  const auto& mats = physics.materials;
  if (a >= mats.size() || b >= mats.size()) return;
  for (const Interaction& x : physics.interactions)
    if ((x.material_a == a && x.material_b == b) || (x.material_a == b && x.material_b == a)) return;
  const std::string pair = "\"" + mats[a].name + "\", \"" + mats[b].name + "\"";
  reader.error(key, "= \"" + mats[b].name + "\": " + how + ", but no [[interaction]] is between [" + pair +
                        "]; they would pass through each other with zero force. Add [[interaction]] with "
                        "between = [" + pair + "], restitution and static_friction (rolling_friction "
                        "optional)");
}

PhysicsConfig read_physics(TomlReader& root) {
  PhysicsConfig cfg;
  if (auto g = root.vec3("gravity_m_s2", Range::closed(-1000.0, 1000.0), false))
    cfg.physics.gravity_m_s2 = *g;

  // Time step: dt_s or a fraction of the Rayleigh step; 1e-12 s to 1 s is every sane DEM step.
  cfg.time_step.dt_s = root.number("dt_s", Range::closed(1e-12, 1.0), 0.0);
  cfg.time_step.rayleigh_fraction_set = root.has("rayleigh_fraction");
  cfg.time_step.rayleigh_fraction = root.number("rayleigh_fraction", Range::left_open(0.0, 1.0), 0.2);
  cfg.time_step.force_dt = root.boolean("force_dt", false);

  if (auto c = root.table("contact")) {
    const std::string model = c->choice("model", {"hertz_mindlin", "hmnr"}, "hertz_mindlin");
    parse_normal_model(model, cfg.physics.contact.normal);
    const std::string rolling = c->choice("rolling", {"none", "cdt", "epsd"}, "none");
    parse_rolling_model(rolling, cfg.physics.contact.rolling);
    // CDT lever arm: "sphere" (the contacting sphere's radius) or "centre_of_mass" (EDEM's
    // standard rolling friction: the contact point's distance from the body's centre of mass).
    cfg.physics.contact.cdt_lever_from_centre_of_mass =
        c->choice("rolling_lever", {"sphere", "centre_of_mass"}, "sphere") == "centre_of_mass";
    // CDT at rest: "static" (the torque at most stops the body's rotation within a step, as Coulomb
    // friction holds a contact) or "literal" (-mu_r |Fn| R w/|w|, which flips every step on a body
    // at rest and shakes a packing under load; contact/rolling_cdt.hpp).
    cfg.physics.contact.cdt_stop_limit = c->choice("cdt_at_rest", {"static", "literal"}, "static") == "static";
    cfg.physics.contact.clip_attractive = c->boolean("clip_attractive", false);
    // Dashpot velocity: "half_step" (v_{n+1/2}, stable in confined packings) or "predicted" (the
    // end-of-step estimate, closer restitution for e <= 0.1 in dilute impacts; contact_model.hpp).
    cfg.physics.contact.dashpot_predicted =
        c->choice("dashpot_velocity", {"half_step", "predicted"}, "half_step") == "predicted";
    cfg.physics.contact.epsd_damping_ratio =
        c->number("epsd_damping_ratio", Range::closed(0.0, 1.0), 0.3);
    c->check_unknown_keys();
  }

  auto mats = root.table("materials");
  if (!mats) {
    root.error("materials", "is required: at least one [materials.NAME] table");
  } else {
    for (const std::string& name : mats->keys()) {
      auto m = mats->table(name);
      if (!m) continue;
      Material mat;
      mat.name = name;
      // Bounds: the physical range of solids (aerogel to tungsten; foams to diamond), a little wider.
      mat.density_kg_m3 = m->number("density_kg_m3", Range::closed(1.0, 1e5));
      mat.youngs_modulus_pa = m->number("youngs_modulus_pa", Range::closed(1e3, 1e15));
      mat.poisson_ratio = m->number("poisson_ratio", Range::closed(0.0, 0.5));
      m->check_unknown_keys();
      cfg.material_index[name] = static_cast<std::uint16_t>(cfg.physics.materials.size());
      cfg.physics.materials.push_back(mat);
    }
    if (cfg.physics.materials.empty()) root.error("materials", "must define at least one material");
  }

  std::set<std::pair<std::uint16_t, std::uint16_t>> seen;
  std::set<std::string> names;
  for (TomlReader& it : root.table_array("interaction")) {
    Interaction x;
    x.name = it.string("name", "");
    if (!x.name.empty() && !names.insert(x.name).second)
      it.error("name", "= \"" + x.name + "\": another interaction has the same name");
    std::vector<std::string> pair;
    x.restitution = it.number("restitution", Range::left_open(0.0, 1.0));
    x.static_friction = it.number("static_friction", Range::closed(0.0, 10.0));
    x.rolling_friction = it.number("rolling_friction", Range::closed(0.0, 10.0), 0.0);
    pair = it.strings("between", 2, 2);
    if (pair.size() == 2) {
      x.material_a = cfg.material(it, "between", pair[0]);
      x.material_b = cfg.material(it, "between", pair[1]);
      const auto key = std::minmax(x.material_a, x.material_b);
      if (!seen.insert({key.first, key.second}).second)
        it.error("between", "= [\"" + pair[0] + "\", \"" + pair[1] + "\"]: this pair already has an interaction");
    }
    it.check_unknown_keys();
    cfg.physics.interactions.push_back(x);
  }
  return cfg;
}

}  // namespace seedcal
