#pragma once
// What `seedcal export` writes out (docs/export.md): one seed as a finished study calibrated it:
// the clump of the chosen model (its spheres in the principal frame, its mass properties), the
// materials and interactions of the study's scene with the calibrated and held values in place, and
// the contact model, read the way a run of that scene reads them.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "solver/scenes/seed_bed.hpp"

namespace seedcal {

struct ExportedModel {
  // Where it comes from (for the exported files' headers).
  std::string study_name;         // empty when read from a scene file alone
  std::string study_dir;
  std::string model_name;         // the chosen [[model]]
  std::string model_reason;       // why that model, in words
  std::string test_name;          // the study test whose scene gave the values
  std::string scene_path;
  std::string particle_description;  // the clump file, as the scene names it
  bool converged = true;
  std::vector<std::string> warnings;  // the study's rig warnings (summary.json: warnings)
  nlohmann::json calibrated = nlohmann::json::object();       // parameter path -> value
  nlohmann::json held_at_nominal = nlohmann::json::object();  // parameter path -> value

  // The values.
  PhysicsSpec physics;            // materials, interactions, contact options, gravity
  TimeStepSpec time_step;
  SeedSpec seeds;                 // template in its principal frame; the scale distribution
  std::uint16_t seed_material = 0;
  // The material the exported deck's walls are made of: the first other material the seeds have an
  // [[interaction]] with (the seed material itself when there is none).
  std::uint16_t wall_material = 0;

  const Material& seed() const { return physics.materials.at(seed_material); }
  // The interaction between materials a and b; nullptr when the scene defines none.
  const Interaction* interaction(std::uint16_t a, std::uint16_t b) const;
  // Volume of the template (mass / density), m3, and the diameter of the sphere of that volume, m.
  double volume_m3() const;
  double volume_equivalent_diameter_m() const;
  // Largest distance of a sphere's surface from the centre of mass, m (the bounding sphere).
  double bounding_radius_m() const;
  double largest_sphere_radius_m() const;
  double smallest_sphere_radius_m() const;
};

// The model a scene file describes after `sets` (--set overrides): its physics and [particle] seed.
// Throws InputError naming the file and key when the scene is not a seed scene or does not read.
ExportedModel exported_model_from_scene(const std::string& scene_path, const std::vector<std::string>& sets);

// The default time step for the exported template at scale 1 (seedcal's rule: the configured
// fraction of the Rayleigh step of the smallest sphere, within the stable limit at `impact_speed_m_s`).
double exported_time_step_s(const ExportedModel& m, double impact_speed_m_s);

}  // namespace seedcal
