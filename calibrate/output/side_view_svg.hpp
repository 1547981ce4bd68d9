#pragma once
// A side view of a scene as SVG, like the paper's binarised images: every sphere projected on a
// vertical plane (x-z by default) as a filled circle, with fitted lines and reference lines drawn
// over it. Coordinates in m; the picture is scaled to `width_px`.
#include <string>
#include <vector>

#include <Eigen/Core>

namespace seedcal {

struct SvgLine {
  double x0, z0, x1, z1;  // m
  std::string colour = "#d62728";
  std::string label;
};

struct SideView {
  std::vector<std::pair<Eigen::Vector2d, double>> circles;  // (x, z), radius
  std::vector<SvgLine> lines;
  std::string title;
  double width_px = 640.0;
};

// Projects world points onto the view plane spanned by `horizontal` and +z.
Eigen::Vector2d project(const Eigen::Vector3d& p, const Eigen::Vector3d& horizontal);

std::string render_svg(const SideView& view);

}  // namespace seedcal
