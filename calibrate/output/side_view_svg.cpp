#include "calibrate/output/side_view_svg.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <sstream>

namespace seedcal {

Eigen::Vector2d project(const Eigen::Vector3d& p, const Eigen::Vector3d& horizontal) {
  return {p.dot(horizontal), p.z()};
}

std::string render_svg(const SideView& v) {
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, z0 = x0, z1 = -x0;
  auto grow = [&](double x, double z, double r) {
    x0 = std::min(x0, x - r); x1 = std::max(x1, x + r);
    z0 = std::min(z0, z - r); z1 = std::max(z1, z + r);
  };
  for (const auto& [c, r] : v.circles) grow(c.x(), c.y(), r);
  for (const SvgLine& l : v.lines) { grow(l.x0, l.z0, 0.0); grow(l.x1, l.z1, 0.0); }
  if (!(x1 > x0)) { x0 = 0; x1 = 1; z0 = 0; z1 = 1; }
  const double pad = 0.05 * std::max(x1 - x0, z1 - z0);
  x0 -= pad; x1 += pad; z0 -= pad; z1 += pad;
  const double scale = v.width_px / (x1 - x0);
  const double h = (z1 - z0) * scale + 30.0;
  auto X = [&](double x) { return (x - x0) * scale; };
  auto Z = [&](double z) { return (z1 - z) * scale + 30.0; };
  std::ostringstream s;
  s.precision(5);
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << v.width_px << "\" height=\"" << h
    << "\" viewBox=\"0 0 " << v.width_px << " " << h << "\">\n"
    << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    << "<text x=\"8\" y=\"20\" font-family=\"sans-serif\" font-size=\"14\">" << v.title << "</text>\n"
    << "<g fill=\"#333\" fill-opacity=\"0.85\">\n";
  for (const auto& [c, r] : v.circles)
    s << "<circle cx=\"" << X(c.x()) << "\" cy=\"" << Z(c.y()) << "\" r=\"" << r * scale << "\"/>\n";
  s << "</g>\n";
  for (const SvgLine& l : v.lines) {
    s << "<line x1=\"" << X(l.x0) << "\" y1=\"" << Z(l.z0) << "\" x2=\"" << X(l.x1) << "\" y2=\""
      << Z(l.z1) << "\" stroke=\"" << l.colour << "\" stroke-width=\"2\"/>\n";
    if (!l.label.empty())
      s << "<text x=\"" << X(l.x1) + 4 << "\" y=\"" << Z(l.z1) << "\" font-family=\"sans-serif\" "
        << "font-size=\"12\" fill=\"" << l.colour << "\">" << l.label << "</text>\n";
  }
  s << "</svg>\n";
  return s.str();
}

}  // namespace seedcal
