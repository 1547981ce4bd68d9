#pragma once
// The `piling` scene (static angle of repose): seeds fill a bottomless cylinder standing on a steel
// plate; the cylinder is lifted slowly and the seeds flow out into a heap; the angle of repose is
// the slope of line fits to the heap's side profile.
//
// Measurement (docs/scenes/piling.md): the heap is cut into `azimuths` sectors; in each, the upper
// envelope of the seeds' spheres against the radius r (columns half a seed wide) is fitted with a
// line z = a + b r over the window [0.2, 0.8] x the heap radius (the foot and the rounded top are
// left out, as in image analysis of heap photos); the angle is atan(-b). Reported: the mean over
// the sectors (both sides of every diametral cut) and its standard deviation.
#include "solver/scenes/line_fit.hpp"
#include "solver/scenes/seed_bed.hpp"

namespace seedcal {

struct PilingSpec {
  PhysicsSpec physics;
  TimeStepSpec time_step;
  SeedSpec seeds;
  std::uint16_t plate_material = 0, tube_material = 0;
  double tube_diameter_m = 0.08;
  double fill_height_m = 0.12;
  double lift_speed_m_s = 0.05;
  int azimuths = 8;
  double window_lo = 0.2, window_hi = 0.8;
  double max_time_s = 6.0;
  int threads = 1;
  std::uint64_t seed = 0;
};

struct PilingResult {
  RunReport run;
  double angle_of_repose_deg = 0.0;
  double angle_sd_deg = 0.0;
  std::vector<double> sector_angles_deg;
  double heap_radius_m = 0.0, heap_height_m = 0.0;
  std::size_t seeds = 0;
  std::vector<std::vector<std::pair<double, double>>> profiles;  // per sector: (r, z)
  std::vector<LineFit> fits;
  std::vector<std::vector<std::pair<Vec3, double>>> spheres;
};

PilingResult run_piling(const PilingSpec& spec);

}  // namespace seedcal
