#include "calibrate/clumps/clump_build.hpp"

#include <stdexcept>

#include "calibrate/clumps/fill.hpp"
#include "calibrate/clumps/moisture.hpp"
#include "store/errors.hpp"

namespace seedcal {

ClumpModel build_clump(const Shape& shape, const ClumpShapeInfo& info, double density_kg_m3,
                       const BuildRequest& q) {
  std::vector<SphereXYZR> spheres;
  double min_radius = 0.0;
  std::string layout;
  try {
    if (q.method == "manual") {
      if (q.smoothness >= 0.0) throw std::invalid_argument("--smoothness applies to --method auto only");
      if (q.min_radius_floor_m > 0.0) throw std::invalid_argument("--min-radius-m applies to --method auto only");
      ManualFillOptions o;
      o.spheres = q.spheres;
      const ManualFillResult r = manual_fill(shape, o);
      spheres = r.spheres;
      layout = r.layout;
    } else if (q.method == "auto") {
      AutoFillOptions o;
      o.smoothness = q.smoothness;
      o.target_spheres = q.spheres;
      o.min_radius_floor_m = q.min_radius_floor_m;
      const AutoFillResult r = auto_fill(shape, o);
      spheres = r.spheres;
      min_radius = r.min_radius_m;
    } else {
      throw std::invalid_argument("--method " + q.method + ": must be manual or auto");
    }
  } catch (const std::invalid_argument& e) {
    throw InputError(std::string("clump build: ") + e.what());
  }
  ClumpModel m = finish_clump(spheres, shape, info, density_kg_m3);
  m.method = q.method;
  m.requested_spheres = q.spheres;
  m.smoothness = q.smoothness;
  m.min_radius_m = min_radius;
  m.layout = layout;
  return m;
}

ClumpShapeInfo variety_shape(const Variety& v, double soak_hours) {
  ClumpShapeInfo info;
  info.kind = "ellipsoid";
  info.ellipsoid = v.shape();
  if (soak_hours > 0.0) {
    const Vec3 g = soaking_growth(v, soak_hours);
    info.ellipsoid.length_m *= g.x();
    info.ellipsoid.width_m *= g.y();
    info.ellipsoid.thickness_m *= g.z();
    info.ellipsoid.hilum_radius_m *= std::cbrt(g.prod());
  }
  return info;
}

double finest_auto_volume_m3(const Shape& shape) {
  AutoFillOptions o;
  o.smoothness = 0.0;
  return union_mass_properties(auto_fill(shape, o).spheres).volume_m3;
}

}  // namespace seedcal
