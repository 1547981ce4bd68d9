#include "calibrate/config/particle_config.hpp"

#include <filesystem>

#include "calibrate/clumps/clump_source.hpp"
#include "solver/clump/mass_properties.hpp"

namespace seedcal {

ParticleConfig read_particle(TomlReader& root, const PhysicsConfig& phys, const std::string& config_path,
                             bool many_seeds) {
  ParticleConfig out;
  auto p = root.table("particle");
  if (!p) {
    root.error("particle", "is required: a [particle] table with material and clump_file or spheres_m");
    return out;
  }
  const std::uint16_t mat = phys.material(*p, "material", p->string("material"));
  out.material = mat;
  if (many_seeds) phys.require_interaction(*p, "material", mat, mat, "the seeds touch each other");
  const double density =
      mat < phys.physics.materials.size() ? phys.physics.materials[mat].density_kg_m3 : 1000.0;
  std::vector<SphereXYZR> spheres;
  const bool has_file = p->has("clump_file"), has_inline = p->has("spheres_m");
  if (has_file == has_inline) {
    p->error("clump_file", "give exactly one of clump_file or spheres_m");
  } else if (has_file) {
    const std::string file = p->string("clump_file");
    out.description = file;
    spheres = load_clump_spheres(resolve_data_path(file, config_path), *p, "clump_file");
  } else {
    out.description = "inline spheres_m";
    for (const auto& row : p->number_rows("spheres_m", 4, 1, 5000)) {
      if (!(row[3] > 0.0)) {
        p->error("spheres_m", "every sphere needs a radius > 0 ([x, y, z, r] in m)");
        spheres.clear();
        break;
      }
      spheres.push_back({Vec3(row[0], row[1], row[2]), row[3]});
    }
    warn_buried_spheres(spheres, "", *p, "spheres_m");
  }
  // Size distribution (Table 5 of the paper: width sd / mean width); truncated at +-2 sd by default.
  out.scale.sd = p->number("scale_sd", Range::closed(0.0, 0.5), 0.0);
  out.scale.lo = p->number("scale_min", Range::left_open(0.0, 1.0), 1.0 - 2.0 * out.scale.sd);
  out.scale.hi = p->number("scale_max", Range::closed(1.0, 3.0), 1.0 + 2.0 * out.scale.sd);
  if (out.scale.sd > 0.0 && out.scale.lo >= out.scale.hi) p->error("scale_min", "must be below scale_max");
  p->check_unknown_keys();
  if (!spheres.empty()) out.body = clump_body(spheres, density, mat);
  return out;
}

}  // namespace seedcal
