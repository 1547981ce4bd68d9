#pragma once
// One call from "a variety (or shape) and a filling request" to a finished clump model.
#include <string>

#include "calibrate/clumps/clump_file.hpp"
#include "calibrate/clumps/variety.hpp"

namespace seedcal {

struct BuildRequest {
  std::string method = "manual";  // "manual" or "auto"
  int spheres = 0;                // manual: required; auto: a count target
  double smoothness = -1.0;       // auto: in [0, 5] (instead of spheres)
  double min_radius_floor_m = 0.0;  // auto: no sphere's r_min below this (0: none)
};

// Throws InputError for an invalid request (message names the option and the allowed range).
ClumpModel build_clump(const Shape& shape, const ClumpShapeInfo& info, double density_kg_m3,
                       const BuildRequest& request);

// The shape of a variety at a soaking time (Table 2 growth; 0 h: the Table 1 means).
ClumpShapeInfo variety_shape(const Variety& v, double soak_hours = 0.0);

// Union volume of the finest automatic model (smoothness 0) of a shape.
double finest_auto_volume_m3(const Shape& shape);

}  // namespace seedcal
