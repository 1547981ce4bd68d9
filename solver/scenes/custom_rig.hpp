#pragma once
// The `custom` scene: a rig the user describes in the scene file (docs/scenes/custom.md). Walls
// (boxes, cylinders, planes, meshes) with a material and optionally a motion law, seeds poured by
// the particle factory from a box, and three phases:
//   fill    the factory pours the seeds in batches, each given `batch_interval_s` to fall
//   settle  until the kinetic energy per seed drops below `settle_energy_ratio` x m g d
//           (settle.hpp), as the other seed scenes settle
//   run     the walls' motions start (each at its own `start_s` after the run began: a gate that
//           slides away, a drum that turns) and the world runs for `run_time_s`, sampled every
//           `sample_interval_s` for the measurements (flow_measures.hpp)
// The solver has no wall removal: a gate is opened by moving it away with its motion law. Seeds
// whose centre falls below `sink_z_m` (optional) are taken out of the world after each sample.
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "solver/scenes/flow_measures.hpp"
#include "solver/scenes/run_plan.hpp"

namespace seedcal {

struct CustomWall {
  Wall wall;  // name, shape, material and its pose at the start
  enum class Motion { none, translate, rotate } motion = Motion::none;
  double start_s = 0.0;  // after the run phase began
  double stop_s = std::numeric_limits<double>::infinity();  // translate: stops then
  Vec3 velocity_m_s = Vec3::Zero();                          // translate
  Vec3 axis = Vec3::UnitZ(), axis_point_m = Vec3::Zero();    // rotate about this line
  double rate_rad_s = 0.0;                                   // rotate
  double lowest_z_m = 0.0;  // lowest point of the shape at the start (the time step's drop height)
};

struct CustomFill {
  BoxRegion region;
  std::size_t count = 0;      // seeds to pour (0: by mass)
  double mass_kg = 0.0;       // mass to pour (0: by count)
  int batches = 20;
  double batch_interval_s = 0.1;
  Vec3 velocity_m_s = Vec3::Zero();
  bool random_orientation = true;
};

struct CustomMeasure {
  enum class Kind { mass_in_region, discharge_rate, surface_height } kind = Kind::mass_in_region;
  std::string name;
  BoxRegion region;                                          // mass_in_region
  Vec3 point_m = Vec3::Zero(), normal = -Vec3::UnitZ();      // discharge_rate
  double fit_lo = 0.2, fit_hi = 0.8;                         // discharge_rate: steady window
  Vec3 from_m = Vec3::Zero(), to_m = Vec3::Zero();           // surface_height: the line
  int points = 11;
  double probe_radius_m = 0.0;
};

struct CustomSpec {
  PhysicsSpec physics;
  TimeStepSpec time_step;
  SeedSpec seeds;
  std::vector<CustomWall> walls;
  CustomFill fill;
  std::vector<CustomMeasure> measures;
  double settle_energy_ratio = 1e-4;
  double settle_max_time_s = 2.0;
  double run_time_s = 1.0;
  double sample_interval_s = 0.005;
  double picture_time_s = 0.5;  // after the run phase began
  std::optional<double> sink_z_m;
  int threads = 1;
  std::uint64_t seed = 0;
  FrameObserver observer;
};

// One measurement's time series over the run phase (time_s from its start).
struct CustomSeries {
  std::vector<double> time_s;
  std::vector<double> value;                 // kg in the region, or kg crossed
  std::vector<std::vector<double>> heights;  // surface_height: per sample, per point (m)
  SteadyRate rate;                           // discharge_rate
};

struct CustomResult {
  RunReport run;
  std::string settle_reason;
  std::size_t seeds_poured = 0, seeds_removed = 0;
  double mass_poured_kg = 0.0;
  std::vector<CustomSeries> series;  // one per spec.measures
  double picture_time_s = 0.0;
  std::vector<std::vector<std::pair<Vec3, double>>> spheres;  // at the picture time
  std::vector<Wall> walls;                                    // at the picture time
};

// The mass the fill pours (its mass, or count x the mean seed mass).
double custom_fill_mass_kg(const CustomSpec& spec);
// The points of a surface_height line: `points` evenly spaced from from_m to to_m.
std::vector<Vec3> surface_line_points(const CustomMeasure& m);

CustomResult run_custom(const CustomSpec& spec);
// What a run of `spec` will simulate (run_plan.hpp).
RunPlan plan_custom(const CustomSpec& spec);

}  // namespace seedcal
