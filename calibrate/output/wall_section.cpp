#include "calibrate/output/wall_section.hpp"

#include "solver/walls/wall_contact_list.hpp"
#include "solver/walls/wall_surface.hpp"

namespace seedcal {

std::vector<SvgLine> wall_section(const std::vector<Wall>& walls, double y_m, const Vec3& region_centre_m,
                                  double region_radius_m, const std::string& colour) {
  std::vector<SvgLine> out;
  for (const Wall& w : walls) {
    TessellationOptions opt;
    opt.region_centre_m = to_wall_frame(w.pose, region_centre_m);
    opt.region_radius_m = region_radius_m;
    SurfaceMesh local = tessellate(*w.shape, opt);
    SurfaceMesh world;
    world.append(local, w.pose.origin_m, w.pose.orientation);
    for (const auto& t : world.triangle) {
      Vec3 v[3];
      double d[3];
      for (int k = 0; k < 3; ++k) {
        v[k] = world.vertex_m[static_cast<std::size_t>(t[static_cast<std::size_t>(k)])];
        d[k] = v[k].y() - y_m;
      }
      std::vector<Vec3> cut;
      for (int k = 0; k < 3; ++k) {
        const int j = (k + 1) % 3;
        if ((d[k] < 0.0) != (d[j] < 0.0)) cut.push_back(v[k] + (v[j] - v[k]) * (d[k] / (d[k] - d[j])));
      }
      if (cut.size() == 2) out.push_back({cut[0].x(), cut[0].z(), cut[1].x(), cut[1].z(), colour, ""});
    }
  }
  return out;
}

}  // namespace seedcal
