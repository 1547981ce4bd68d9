#pragma once
// The `piling` scene (static angle of repose): seeds fill a bottomless cylinder standing on a steel
// plate; the cylinder is lifted slowly and the seeds flow out into a heap; the angle of repose is
// the slope of line fits to the heap's side profile.
//
// Measurement (docs/scenes/piling.md, measure_heap below): the heap is cut into `azimuths`
// sectors; in each, the upper envelope of the seeds' spheres against the radius r (a strip one seed
// wide, columns half a seed wide) is fitted with a line z = a + b r where the side is between
// [0.2, 0.8] x the sector's heap height, outward of its top and inward of its foot (the rounded
// top and the foot are left out, as in image analysis of heap photos); the angle is atan(-b).
// The foot is the first column outward of the top whose envelope is down to one seed lying on
// the plate (z <= one seed size): seeds that ran out alone over the plate are not the heap's
// side. Reported: the mean over the sectors (both sides of every diametral cut) and its sd.
#include "solver/scenes/line_fit.hpp"
#include "solver/scenes/run_plan.hpp"

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
  FrameObserver observer;  // frames for a trajectory (optional)
};

struct PilingResult {
  RunReport run;
  double angle_of_repose_deg = 0.0;
  double angle_sd_deg = 0.0;
  std::vector<double> sector_angles_deg;
  double heap_radius_m = 0.0, heap_height_m = 0.0;
  std::size_t seeds = 0;
  double foot_radius_m = 0.0;
  double lift_m = 0.0;  // how far the tube was lifted
  std::vector<std::vector<std::pair<double, double>>> profiles;  // per sector: (r, z)
  std::vector<LineFit> fits;
  std::vector<std::pair<double, double>> fit_ranges;
  std::vector<std::vector<std::pair<Vec3, double>>> spheres;
};

// The heap's angle from its spheres (world centre, radius) and the bodies' centres; `seed_size_m`
// is the largest extent of one seed (the strip width, twice the column width, and the height of
// one seed lying on the plate). Heights are above the plate at z = 0.
struct HeapMeasurement {
  double angle_deg = 0.0, angle_sd_deg = 0.0;
  std::vector<double> sector_angles_deg;
  double heap_radius_m = 0.0;       // radius holding 95 % of the bodies' centres
  double heap_height_m = 0.0;       // highest sphere top
  double foot_radius_m = 0.0;       // mean over the sectors of the foot's radius
  std::vector<std::vector<std::pair<double, double>>> profiles;  // per sector: (r, z)
  std::vector<LineFit> fits;
  std::vector<std::pair<double, double>> fit_ranges;  // per sector: r range of the fitted columns
};
HeapMeasurement measure_heap(const std::vector<std::pair<Vec3, double>>& spheres,
                             const std::vector<Vec3>& body_centres, double seed_size_m, int azimuths,
                             double window_lo, double window_hi);

PilingResult run_piling(const PilingSpec& spec);
// What a run of `spec` will simulate (run_plan.hpp).
RunPlan plan_piling(const PilingSpec& spec);

}  // namespace seedcal
