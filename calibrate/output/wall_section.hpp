#pragma once
// Walls in a side view: each wall's surface (solver/walls/wall_surface.hpp, placed by its pose) cut
// by the vertical plane y = y_m, as line segments in the view's (x, z). A triangle whose vertices lie
// on both sides of the plane gives one segment between the points where its two crossing edges meet
// the plane (linear interpolation along each edge).
#include <string>
#include <vector>

#include "calibrate/output/side_view_svg.hpp"
#include "solver/walls/wall.hpp"

namespace seedcal {

// `region_centre_m` and `region_radius_m` (world): the ball a plane's drawn patch must cover.
std::vector<SvgLine> wall_section(const std::vector<Wall>& walls, double y_m, const Vec3& region_centre_m,
                                  double region_radius_m, const std::string& colour);

}  // namespace seedcal
