#pragma once
// A seed variety as measured (data/varieties/NAME.toml): density, moisture, tri-axial dimensions,
// width distribution, soaking and moisture-modulus tables, the paper's clump volumes (Table 4), the
// physical-test targets, its DEM values (Table 6: [simulation] for the seed and seed-seed contact,
// [material_contact.NAME] for the seed on a rig material) and its clump models ([models], with
// `default_model`). It is the one source of a seed's properties: a scene names it and takes them
// from it (calibrate/config/variety_scene.hpp). Reading validates every value and names file, key
// and range.
#include <map>
#include <string>
#include <vector>

#include "calibrate/clumps/seed_shape.hpp"

namespace seedcal {

struct PaperClump {
  std::string filling;  // "manual" or "automatic"
  int spheres = 0;
  double volume_m3 = 0.0;
  double ratio = 0.0;   // to the variety's finest automatic clump, as printed
  std::string flag;     // a note where the printed value looks wrong
};

struct Variety {
  std::string name, file;
  double density_kg_m3 = 0, moisture_fraction = 0, thousand_seed_mass_kg = 0;
  int best_compromise_spheres = 0;
  double length_m = 0, length_sd_m = 0, width_m = 0, width_sd_m = 0, thickness_m = 0,
         thickness_sd_m = 0;
  double width_mean_m = 0, width_dist_sd_m = 0;  // Table 5
  double hilum_radius_m = 0, hilum_centre = 0.85;
  std::vector<double> soak_hours;
  std::vector<Vec3> soak_before_m, soak_after_m;  // L, W, T
  std::vector<double> mc_moisture_fraction, mc_youngs_modulus_pa;
  std::string mc_flag;
  std::vector<PaperClump> paper_clumps;
  std::map<std::string, double> simulation, targets;  // Table 6 seed column; section 3.1
  std::map<std::string, std::string> flags;           // "targets.bulk_density_flag" -> text
  // Seed-to-material contact: material name -> restitution, static_friction, rolling_friction.
  std::map<std::string, std::map<std::string, double>> material_contact;
  std::map<std::string, std::string> models;  // clump model name -> clump file (resolved, exists)
  std::string default_model;                  // one of `models`; "" when it names none

  EllipsoidSpec shape() const;  // mean L x W x T and the hilum settings
};

// NAME ("jinong1") or a path to a .toml file. A name is looked up as data/varieties/NAME.toml
// under the working directory, then under $SEEDCAL_DATA_DIR/varieties. Throws InputError.
std::string variety_path(const std::string& name_or_path);
Variety read_variety(const std::string& name_or_path);

// The clump file of model `name` of the variety; InputError naming the variety's models otherwise.
std::string variety_model_file(const Variety& v, const std::string& name);

}  // namespace seedcal
