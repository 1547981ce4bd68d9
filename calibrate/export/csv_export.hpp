#pragma once
// The CSV export, for packages other than LIGGGHTS (docs/export.md):
//   DIR/spheres.csv     sphere,x_m,y_m,z_m,radius_m: the clump in its principal frame (centre of
//                       mass at the origin, axes along the principal axes, ascending moments)
//   DIR/parameters.csv  key,value,unit,meaning: the materials, interactions, contact model and
//                       particle keys under their seedcal config names (each one a `--set` of the
//                       scene), then the clump's mass properties (clump.*)
// Both start with '#' comment lines: where the values come from and what does not carry over
// exactly to LIGGGHTS (most readers skip them: pandas' comment='#', numpy's default).
#include <string>

#include "calibrate/export/exported_model.hpp"

namespace seedcal {

std::string spheres_csv(const ExportedModel& m);
std::string parameters_csv(const ExportedModel& m);

// Writes DIR/spheres.csv and DIR/parameters.csv (each atomically; DIR is created).
void write_csv_export(const ExportedModel& m, const std::string& dir);

}  // namespace seedcal
