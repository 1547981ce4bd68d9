#pragma once
// A built clump model and its TOML file (written by `seedcal clump build`, read by `clump info`,
// the scenes' [particle] clump_file and the tests):
//   format = "seedcal-clump-1"
//   name = "jinong1-manual-9"
//   spheres_m = [[x, y, z, r], ...]        # body frame: centroid at 0, principal axes
//   [mass_properties]  volume_m3, volume_rel_error, density_kg_m3, mass_kg, principal_inertia_kg_m2
//   [body_frame]       origin_in_shape_m, axes_in_shape  (p_shape = origin + sum p_body[i] axes[i])
//   [shape]            kind = "ellipsoid" (length_m, width_m, thickness_m, hilum_radius_m,
//                      hilum_centre) or "scan" (path, relative to this file's folder; unit "m" or
//                      "mm"; weld_m; align = "principal" or "none"; scan.hpp), volume_m3.
//                      kind = "stl" (path, in m, as it is) is read as an older scan.
//   [fill]             method, spheres, smoothness, min_radius_m, iou, iou_error, layout
//   [provenance]       seedcal_version, command, variety, variety_file, soak_hours
#include <memory>
#include <string>
#include <vector>

#include "calibrate/clumps/seed_shape.hpp"

namespace seedcal {

struct ClumpShapeInfo {
  std::string kind = "ellipsoid";  // or "scan"
  EllipsoidSpec ellipsoid;
  ScanSpec scan;  // the path as the clump file resolves it (its folder, or as written)
};

// Throws InputError when the shape cannot be made (bad STL, bad dimensions).
std::unique_ptr<Shape> make_shape(const ClumpShapeInfo& info);

struct ClumpModel {
  std::string name;
  std::vector<SphereXYZR> spheres;  // body frame
  Vec3 origin_in_shape_m = Vec3::Zero();
  Mat3 axes_in_shape = Mat3::Identity();  // columns: body axes in the shape frame
  double volume_m3 = 0, volume_rel_error = 0, density_kg_m3 = 0, mass_kg = 0;
  Vec3 principal_inertia_kg_m2 = Vec3::Zero();
  ClumpShapeInfo shape;
  double target_volume_m3 = 0;
  std::string method;       // "manual", "auto" or "imported"
  int requested_spheres = 0;
  double smoothness = -1;   // auto by smoothness only
  double min_radius_m = 0;  // auto only
  double iou = 0, iou_error = 0;
  std::string layout;       // manual only
  std::string seedcal_version, command, variety, variety_file;
  double soak_hours = 0;

  std::vector<SphereXYZR> spheres_in_shape_frame() const;
};

// Mass properties, body frame and IoU from spheres in the shape's frame.
ClumpModel finish_clump(const std::vector<SphereXYZR>& spheres_shape_frame, const Shape& shape,
                        const ClumpShapeInfo& info, double density_kg_m3);

std::string clump_file_text(const ClumpModel& m);
void write_clump_file(const std::string& path, const ClumpModel& m);  // atomic
ClumpModel read_clump_file(const std::string& path);                  // throws InputError

}  // namespace seedcal
