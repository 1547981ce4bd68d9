#pragma once
// Small worlds shared by the physics tests: one material, one interaction, spheres and planes.
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "solver/clump/mass_properties.hpp"
#include "solver/sim/simulation.hpp"

namespace seedcal::testing {

struct MaterialSpec {
  double density_kg_m3 = 2800.0;
  double youngs_modulus_pa = 4.8e10;
  double poisson_ratio = 0.2;
  double restitution = 0.9;
  double static_friction = 0.35;
  double rolling_friction = 0.0;
};

// The paper's Table 6 seed and seed-seed contact (Jinong 1): density 1340 kg/m3, E 1.65e8 Pa,
// nu 0.4, restitution 0.45, static friction 0.55, rolling friction 0.05.
inline MaterialSpec table6_seed() {
  MaterialSpec m;
  m.density_kg_m3 = 1340.0;
  m.youngs_modulus_pa = 1.65e8;
  m.poisson_ratio = 0.4;
  m.restitution = 0.45;
  m.static_friction = 0.55;
  m.rolling_friction = 0.05;
  return m;
}

// Material 0 for the particles; material 1 for walls (its own modulus, same interaction
// coefficients with material 0).
inline InteractionTable make_table(const MaterialSpec& m, double wall_modulus_pa = -1.0,
                                   double wall_poisson = -1.0) {
  std::vector<Material> mats = {
      {"particle", m.density_kg_m3, m.youngs_modulus_pa, m.poisson_ratio},
      {"wall", 7800.0, wall_modulus_pa > 0 ? wall_modulus_pa : m.youngs_modulus_pa,
       wall_poisson >= 0 ? wall_poisson : m.poisson_ratio}};
  std::vector<Interaction> its = {
      {"pp", 0, 0, m.restitution, m.static_friction, m.rolling_friction},
      {"pw", 0, 1, m.restitution, m.static_friction, m.rolling_friction}};
  return InteractionTable(mats, its);
}

inline Wall plane_wall(const Vec3& point, const Vec3& normal) {
  Wall w;
  w.name = "plane";
  w.shape = std::make_shared<PlaneShape>(normal);
  w.material = 1;
  w.pose.origin_m = point;
  return w;
}

// One body resting on (or rolling over) the plane z = 0, stepped at `fraction` of its Rayleigh
// step (the options' dt_s is replaced).
inline Simulation body_on_plane(const InteractionTable& table, SimulationOptions opt, const BodyDef& body,
                                double fraction = 0.2) {
  opt.dt_s = 1e-6;  // any; only the Rayleigh step is read
  Simulation probe(table, opt);
  probe.add_body(body);
  opt.dt_s = fraction * probe.rayleigh_time_step_s();
  Simulation sim(table, opt);
  sim.add_body(body);
  sim.add_wall(plane_wall(Vec3::Zero(), Vec3::UnitZ()));
  return sim;
}

// The spheres of a clump file of "x y z r" lines in metres (data/bench/clump9.txt: the nine-sphere
// seed of the peer benchmark); empty when the file cannot be read.
inline std::vector<SphereXYZR> read_xyzr(const std::string& path) {
  std::ifstream in(path);
  std::vector<SphereXYZR> spheres;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ls(line);
    double x, y, z, r;
    if (ls >> x >> y >> z >> r) spheres.push_back({Vec3(x, y, z), r});
  }
  return spheres;
}

// Effective modulus of two materials: 1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2.
inline double e_star(double e1, double nu1, double e2, double nu2) {
  return 1.0 / ((1.0 - nu1 * nu1) / e1 + (1.0 - nu2 * nu2) / e2);
}

}  // namespace seedcal::testing
