#pragma once
// A scene's seed properties from the variety it names. A scene file says
//   variety = "../../varieties/jinong1.toml"   # a variety file (relative to the scene) or a name
//   [particle] model = "manual-9"              # optional: one of the variety's [models]
// and the variety supplies, wherever the scene file leaves them out:
//   materials.seed.density_kg_m3, youngs_modulus_pa, poisson_ratio     <- [simulation]
//   the seed_seed interaction: restitution, static_friction, rolling_friction <- [simulation]
//   a seed_M interaction for every material M the scene defines that the variety's
//     [material_contact.M] describes (Table 6's seed-to-material columns)
//   [particle] material = "seed", scale_sd = width sd / mean width       <- [width_distribution]
//   [particle] clump file: model, or the variety's default_model when the scene gives no
//     clump_file, spheres_m or model (resolved when the particle is read: particle_config.cpp).
// A value the scene file itself gives wins and is reported as replacing the variety's; `--set`
// overrides are applied after this expansion, so they win silently, as they do everywhere.
#include <string>
#include <vector>

#include <toml.hpp>

namespace seedcal {

struct VarietyDefaults {
  std::string variety_file;              // "" when the scene names no variety
  std::vector<std::string> filled;       // dotted keys taken from the variety
  std::vector<std::string> replaced;     // "KEY = scene value replaces the variety's VALUE"
  std::vector<std::string> repeated;     // keys the scene file gives with the variety's own value
};

// The variety file a scene document names (resolved against the scene file), or "".
std::string scene_variety_file(const toml::value& doc, const std::string& scene_path);

// Fills `doc`'s seed properties from its variety, as the header says. Throws InputError naming the
// scene and the variety file when the variety lacks a value the scene needs.
VarietyDefaults apply_variety(toml::value& doc, const std::string& scene_path);

// The clump file the scene's particle uses: its clump_file, or its model's (or the variety's default
// model's) file; "" for inline spheres. Paths resolved; throws InputError for an unknown model.
std::string scene_clump_file(const toml::value& doc, const std::string& scene_path);

}  // namespace seedcal
