#include "calibrate/config/particle_config.hpp"

#include <filesystem>

#include "calibrate/clumps/clump_source.hpp"
#include "calibrate/clumps/variety.hpp"
#include "calibrate/config/variety_scene.hpp"
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
  // The variety (variety_scene.hpp) has already supplied the seed's values; what is left here is
  // the clump model it names.
  const std::string variety = root.string("variety", "");
  const bool has_file = p->has("clump_file"), has_inline = p->has("spheres_m"), has_model = p->has("model");
  if (static_cast<int>(has_file) + static_cast<int>(has_inline) + static_cast<int>(has_model) > 1) {
    p->error(has_model ? "model" : "clump_file", "give only one of clump_file, spheres_m or model");
  } else if (has_model || (!has_file && !has_inline && !variety.empty())) {
    const std::string model = has_model ? p->string("model") : "";
    try {
      const Variety v = read_variety(scene_variety_file(root.value(), config_path));
      if (!has_model && v.default_model.empty()) {
        p->error("clump_file", "is required: the variety " + v.file + " names no default_model (give model, "
                               "clump_file or spheres_m)");
      } else {
        out.clump_file = variety_model_file(v, has_model ? model : v.default_model);
        out.description = (has_model ? model : v.default_model) + " (" + out.clump_file + ")";
        spheres = load_clump_spheres(out.clump_file, *p, has_model ? "model" : "clump_file");
      }
    } catch (const InputError& e) {
      for (const std::string& problem : e.problems()) p->error(has_model ? "model" : "variety", "= \"" +
                                                                   (has_model ? model : variety) + "\": " + problem);
    }
  } else if (!has_file && !has_inline) {
    p->error("clump_file", "give one of clump_file, spheres_m, or model with a variety");
  } else if (has_file) {
    const std::string file = p->string("clump_file");
    out.description = file;
    out.clump_file = resolve_data_path(file, config_path);
    spheres = load_clump_spheres(out.clump_file, *p, "clump_file");
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
