#pragma once
// Corners of the parameter space for the stability sweep (stability_sweep_test.cpp) and for the
// measured table of docs/results/stability.md: one particle (a sphere or a clump) against a steel plate,
// run through the solver's own scenes (impact, free_drop, bulk_density) in-process.
#include <cstdint>
#include <string>
#include <vector>

#include "solver/clump/mass_properties.hpp"
#include "solver/contact/contact_model.hpp"

namespace seedcal::stability {

// The particle of a corner.
enum class Shape {
  sphere,       // one sphere, r = 4 mm
  seed9,        // the nine-sphere Jinong 1 clump of data/bench/clump9.txt (9.6 x 9.1 x 7.9 mm)
  ratio20,      // a 4 mm sphere with six 0.2 mm bumps (radius ratio 1:20) standing 0.1 mm out
  spheres2000,  // 2,000 spheres of 0.5 mm on a 0.7 mm lattice (a 10 x 10 x 20 block, 7 x 7 x 14 mm)
};
const char* to_string(Shape s);
std::vector<SphereXYZR> shape_spheres(Shape s);

// One corner. Defaults: Jinong 1 seed on steel, Table 6 of the paper as in
// data/scenes/jinong1/free_drop.toml.
struct Corner {
  std::string name;
  double youngs_modulus_pa = 1.65e8;
  double poisson_ratio = 0.4;
  double density_kg_m3 = 1340.0;
  double restitution = 0.65;
  double static_friction = 0.4;
  double rolling_friction = 0.05;
  RollingModel rolling = RollingModel::cdt;
  NormalModel normal = NormalModel::hmnr;
  Shape shape = Shape::seed9;
  bool dashpot_predicted = false;  // ContactOptions::dashpot_predicted
};

// What became of one run.
enum class Verdict {
  ok,           // completed, energy bounded, indices finite and sane
  refused,      // a setting was refused before the run (SettingError)
  stopped,      // a stability guard stopped the run (NaN, runaway energy, deep overlap)
  energy_gain,  // completed, but the energy rose above the bound
  bad_index,    // completed, but an index is not finite or out of its range
};
const char* to_string(Verdict v);

struct Outcome {
  Verdict verdict = Verdict::ok;
  std::string message;      // the refusal, the guard's message, or what was wrong
  std::string refused_key;  // SettingError::key() of a refusal
  double dt_s = 0.0;
  double restitution_out = 0.0;      // rebound / impact normal speed (impact: spheres only)
  double max_energy_ratio = 0.0;     // largest energy over the energy at the start
  double contact_time_s = 0.0;       // first impact, measured (impact scene)
  double steps_per_contact = 0.0;    // elastic Hertz contact time (time_step.hpp) / dt_s
  std::uint64_t steps = 0;
  std::string stop_reason;
  double deepest_overlap_fraction = 0.0;  // RunReport's: past half the smaller radius, else 0
};

// A free body may end with at most this much more energy than it had: 1 % (a correct explicit
// integrator loses or gains O((dt/t_c)^2) of the energy per contact; at the 10 steps per contact
// of the stable limit, a lossless e = 1 contact measures within 0.3 %, docs/stability.md).
inline constexpr double kEnergyGainBound = 0.01;

// Time-step choice of a run: fraction <= 0 is the default (0.2 of the Rayleigh step, lowered to
// the stable limit); otherwise rayleigh_fraction = fraction set by the user, refused above the
// stable limit unless `force`.
struct StepChoice {
  double fraction = 0.0;
  bool force = false;
  double dt_s = 0.0;  // > 0: this dt_s instead of a fraction
};

// The impact scene without gravity: the particle, 0.5 mm above the plate, moves down at
// speed_m_s (1.7155 m/s: free fall from 150 mm) for the time of its first contact and a little
// more. restitution_out is the rebound over the impact speed (spheres only: a clump turns);
// max_energy_ratio the largest kinetic energy over the initial (no gravity, so it may not rise).
// gap_m: the starting distance to the plate (sets where within a step the contact begins).
Outcome impact(const Corner& c, StepChoice step, double speed_m_s = 1.7155, double gap_m = 0.0005);

// The free_drop scene (gravity, 150 mm onto steel, a fixed orientation for spheres, the scene's
// random one from seed 1 for clumps); restitution_out from its impact and rebound speeds.
Outcome free_drop(const Corner& c, StepChoice step, double drop_height_m = 0.150);

// The bulk_density scene in a small steel box (container_m cube, quick protocol): completes with
// a solid fraction in (0.2, 0.8) when ok.
Outcome bed(const Corner& c, StepChoice step, double container_m = 0.03, double max_time_s = 0.6);

}  // namespace seedcal::stability
