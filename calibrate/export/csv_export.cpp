#include "calibrate/export/csv_export.hpp"

#include <filesystem>

#include "calibrate/export/export_notes.hpp"
#include "store/atomic_file.hpp"

namespace seedcal {
namespace {

// RFC 4180: a field with a comma, a quote or a line break is quoted, its quotes doubled.
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

struct CsvRows {
  std::string text;
  void add(const std::string& key, const std::string& value, const std::string& unit, const std::string& meaning) {
    text += csv_field(key) + "," + csv_field(value) + "," + csv_field(unit) + "," + csv_field(meaning) + "\n";
  }
  void add(const std::string& key, double value, const std::string& unit, const std::string& meaning) {
    add(key, exact_number_text(value), unit, meaning);
  }
};

std::string csv_header(const ExportedModel& m, const std::string& title) {
  std::vector<std::string> h{title};
  for (const std::string& line : provenance_lines(m)) h.push_back(line);
  h.push_back("");
  h.push_back("What does not carry over exactly to LIGGGHTS (the same holds for a package with its contact models):");
  for (const std::string& note : carry_over_notes(m)) h.push_back("- " + note);
  return comment_block(h, "# ");
}

}  // namespace

std::string spheres_csv(const ExportedModel& m) {
  std::string s = csv_header(m, "seedcal export: the clump's spheres in its principal frame (centre of mass at the "
                            "origin, axes along the principal axes of inertia, ascending moments), m (docs/export.md)");
  s += "sphere,x_m,y_m,z_m,radius_m\n";
  int k = 0;
  for (const SphereDef& sp : m.seeds.body.spheres)
    s += std::to_string(++k) + "," + exact_number_text(sp.offset_m.x()) + "," + exact_number_text(sp.offset_m.y()) + "," +
         exact_number_text(sp.offset_m.z()) + "," + exact_number_text(sp.radius_m) + "\n";
  return s;
}

std::string parameters_csv(const ExportedModel& m) {
  const ContactOptions& c = m.physics.contact;
  const auto& mats = m.physics.materials;
  CsvRows r;
  for (const Material& mat : mats) {
    const std::string k = "materials." + mat.name + ".";
    r.add(k + "density_kg_m3", mat.density_kg_m3, "kg/m3", "density of " + mat.name);
    r.add(k + "youngs_modulus_pa", mat.youngs_modulus_pa, "Pa", "Young's modulus of " + mat.name);
    r.add(k + "poisson_ratio", mat.poisson_ratio, "1", "Poisson's ratio of " + mat.name);
  }
  for (const Interaction& i : m.physics.interactions) {
    const std::string between = mats[i.material_a].name + " and " + mats[i.material_b].name;
    r.add(i.name + ".restitution", i.restitution, "1", "coefficient of restitution between " + between);
    r.add(i.name + ".static_friction", i.static_friction, "1", "coefficient of static friction between " + between);
    r.add(i.name + ".rolling_friction", i.rolling_friction, "1", "coefficient of rolling friction between " + between);
  }
  r.add("contact.model", to_string(c.normal), "", "normal and tangential contact (docs/contact_models.md)");
  r.add("contact.rolling", to_string(c.rolling), "", "rolling resistance model");
  r.add("contact.rolling_lever", c.cdt_lever_from_centre_of_mass ? "centre_of_mass" : "sphere", "",
        "CDT lever: the contacting sphere's radius, or the contact point's distance from the centre of mass");
  r.add("contact.cdt_at_rest", c.cdt_stop_limit ? "static" : "literal", "",
        "CDT on a body at rest: held (static) or the sign function (literal)");
  r.add("contact.clip_attractive", c.clip_attractive ? "true" : "false", "", "normal force clipped at zero");
  r.add("contact.dashpot_velocity", c.dashpot_predicted ? "predicted" : "half_step", "",
        "the velocity the dashpots see");
  r.add("contact.epsd_damping_ratio", c.epsd_damping_ratio, "1", "EPSD rolling dashpot's damping ratio");
  const Vec3 g = m.physics.gravity_m_s2;
  r.add("gravity_m_s2", "[" + exact_number_text(g.x()) + ", " + exact_number_text(g.y()) + ", " + exact_number_text(g.z()) + "]", "m/s2",
        "gravity");
  r.add("particle.material", m.seed().name, "", "the seeds' material");
  r.add("particle.scale_sd", m.seeds.scale.sd, "1", "sd of the seeds' size factor (normal, mean 1)");
  if (m.seeds.scale.sd > 0.0) {
    r.add("particle.scale_min", m.seeds.scale.lo, "1", "smallest size factor");
    r.add("particle.scale_max", m.seeds.scale.hi, "1", "largest size factor");
  }
  const BodyDef& b = m.seeds.body;
  r.add("clump.spheres", static_cast<double>(b.spheres.size()), "1", "spheres in the clump (spheres.csv)");
  r.add("clump.mass_kg", b.mass_kg, "kg", "mass of the clump at scale 1 (the union of its spheres x density)");
  r.add("clump.volume_m3", m.volume_m3(), "m3", "volume of the union of its spheres (mass / density)");
  r.add("clump.volume_equivalent_diameter_m", m.volume_equivalent_diameter_m(), "m",
        "diameter of the sphere of the same volume");
  r.add("clump.principal_inertia_x_kg_m2", b.principal_inertia_kg_m2.x(), "kg m2", "moment of inertia about x");
  r.add("clump.principal_inertia_y_kg_m2", b.principal_inertia_kg_m2.y(), "kg m2", "moment of inertia about y");
  r.add("clump.principal_inertia_z_kg_m2", b.principal_inertia_kg_m2.z(), "kg m2", "moment of inertia about z");
  r.add("clump.bounding_radius_m", m.bounding_radius_m(), "m", "largest distance of its surface from the centre of mass");
  return csv_header(m, "seedcal export: the seed's parameters; keys other than clump.* are seedcal scene config keys "
                   "(--set KEY=VALUE), SI units (docs/export.md)") +
         "key,value,unit,meaning\n" + r.text;
}

void write_csv_export(const ExportedModel& m, const std::string& dir) {
  std::filesystem::create_directories(dir);
  write_file_atomic(dir + "/spheres.csv", spheres_csv(m));
  write_file_atomic(dir + "/parameters.csv", parameters_csv(m));
}

}  // namespace seedcal
