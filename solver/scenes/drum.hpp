#pragma once
// The `drum` scene (dynamic angle of repose): a steel drum (inner diameter 200 mm, 50 mm deep in
// the paper) turning about its horizontal axis, filled to a filling rate (11.04 % in the paper) of
// its volume with seeds, turned at a set speed; the dynamic angle of repose is the slope of a line
// fitted to the free surface at set times (3, 4 and 5 s in the paper), averaged.
//
// Filling (docs/scenes/drum.md): the paper's filling rate f relates the bed height h to the drum
// radius Rc by f = (eps - sin eps cos eps) / pi, eps = arccos(1 - h / Rc); the scene reports h. The
// seed mass is f x the drum volume x `bulk_density_kg_m3` (the bulk density of the seeds, a rig
// key; the bulk_density scene measures it). Speed from `speed_rpm` (the Froude number
// Fr = w^2 Rc / g is reported).
// Surface: the seeds' spheres are projected on the plane normal to the axis; the upper envelope in
// columns half a seed wide, restricted to the central `fit_width_fraction` of the bed's chord,
// is fitted with a line; the angle is atan(|slope|).
#include "solver/scenes/line_fit.hpp"
#include "solver/scenes/run_plan.hpp"

namespace seedcal {

struct DrumSpec {
  PhysicsSpec physics;
  TimeStepSpec time_step;
  SeedSpec seeds;
  std::uint16_t drum_material = 0;
  double diameter_m = 0.2;
  double depth_m = 0.05;
  double filling_rate = 0.1104;
  double bulk_density_kg_m3 = 680.0;
  double speed_rpm = 5.0;
  std::vector<double> frame_times_s = {3.0, 4.0, 5.0};  // after the drum starts turning
  double fit_width_fraction = 0.6;
  // 0: a smooth circular shell. N >= 3: the shell is a prism of N flat facets inscribed in the
  // circle (a drum made of plates, or a CAD drum as a triangle mesh), whose edges give the seeds a
  // geometric grip the smooth shell does not.
  int shell_facets = 0;
  int threads = 1;
  std::uint64_t seed = 0;
  FrameObserver observer;  // frames for a trajectory (optional)
};

struct DrumFrame {
  double time_s, angle_deg;
  std::vector<std::pair<double, double>> surface;  // (x, z) in the drum's cross-section
  LineFit fit;
  // Mass-weighted mean speed, along the drum's turn, of the seeds whose centre lies within one
  // seed length of the drum's shell, over the shell's speed at their radius: about 1 when the
  // wall carries the bed up (rolling, cascading), about 0 when the shell slides under a bed that
  // stays put (the slipping regime, where the surface angle is set by the wall friction and not
  // by the seeds' avalanches; Mellmann 2001, Powder Technol. 118, 251-270).
  double wall_layer_speed_ratio = 0.0;
};

struct DrumResult {
  RunReport run;
  double dynamic_angle_of_repose_deg = 0.0;
  double angle_sd_deg = 0.0;
  int measured_frames = 0;  // frames whose surface line fit succeeded: the mean and sd are over these
  int failed_frames = 0;    // frames whose fit failed (fewer than 3 surface points in the fit band)
  double wall_layer_speed_ratio = 0.0;  // mean over the frames (DrumFrame)
  // Frames in which the shell slides under a bed at rest (|ratio| < kSlippingSpeedRatio,
  // Mellmann's slipping regime): their angle is held by the wall friction, not a dynamic angle of
  // repose (docs/scenes/drum.md).
  int slipping_frames = 0;
  double froude_number = 0.0;
  double fill_height_m = 0.0;
  std::size_t seeds = 0;
  std::vector<DrumFrame> frames;
  std::vector<std::vector<std::pair<Vec3, double>>> spheres;  // at the last frame
};

// The dynamic angle over the frames whose surface line fit succeeded (DrumFrame::fit.ok): mean,
// sample sd (n - 1; 0 for one frame) and the counts of measured and failed frames. The mean is NaN
// when no frame was measured. Sets the four fields of `res` from res.frames.
void summarize_frame_angles(DrumResult& res);

// Bed height for a filling rate: solves f = (eps - sin eps cos eps) / pi for eps, h = Rc (1 - cos eps).
double drum_fill_height(double radius_m, double filling_rate);

// A frame whose wall layer moves at less than this fraction of the shell's speed (either way) is
// counted as slipping.
inline constexpr double kSlippingSpeedRatio = 0.1;

// DrumFrame::wall_layer_speed_ratio of a drum of inner radius `radius_m` turning at `omega_rad_s`
// about +y through the origin, over the bodies whose centre lies within `layer_m` of the shell
// (0 when none does or the drum stands still).
double wall_layer_speed_ratio(const BodyState& bodies, double radius_m, double layer_m,
                              double omega_rad_s);

DrumResult run_drum(const DrumSpec& spec);
// What a run of `spec` will simulate (run_plan.hpp).
RunPlan plan_drum(const DrumSpec& spec);

}  // namespace seedcal
