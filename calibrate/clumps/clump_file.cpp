#include "calibrate/clumps/clump_file.hpp"

#include <cstdio>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "calibrate/config/toml_reader.hpp"
#include "store/atomic_file.hpp"

namespace seedcal {
namespace {

std::string num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  std::string s(buf);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";  // TOML float, not integer
  return s;
}

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (c == '\n') { out += "\\n"; continue; }
    out += c;
  }
  return out + "\"";
}

std::string vec(const Vec3& v) {
  std::string s = "[";
  s.append(num(v.x())).append(", ").append(num(v.y())).append(", ").append(num(v.z())).append("]");
  return s;
}

}  // namespace

std::unique_ptr<Shape> make_shape(const ClumpShapeInfo& info) {
  try {
    if (info.kind == "scan") return std::make_unique<MeshShape>(MeshShape::from_scan(info.scan));
    return std::make_unique<EllipsoidShape>(info.ellipsoid);
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what());
  }
}

std::vector<SphereXYZR> ClumpModel::spheres_in_shape_frame() const {
  std::vector<SphereXYZR> out;
  for (const auto& s : spheres) out.push_back({origin_in_shape_m + axes_in_shape * s.centre_m, s.radius_m});
  return out;
}

ClumpModel finish_clump(const std::vector<SphereXYZR>& in_shape, const Shape& shape,
                        const ClumpShapeInfo& info, double density_kg_m3) {
  ClumpModel m;
  const UnionMassProperties mp = union_mass_properties(in_shape);
  m.origin_in_shape_m = mp.centroid_m;
  m.axes_in_shape = mp.principal_axes;
  for (const auto& s : in_shape)
    m.spheres.push_back({mp.principal_axes.transpose() * (s.centre_m - mp.centroid_m), s.radius_m});
  m.volume_m3 = mp.volume_m3;
  m.volume_rel_error = mp.volume_rel_error_bound;
  m.density_kg_m3 = density_kg_m3;
  m.mass_kg = density_kg_m3 * mp.volume_m3;
  m.principal_inertia_kg_m2 = density_kg_m3 * mp.principal_moments_unit_density;
  m.shape = info;
  m.target_volume_m3 = shape.volume_m3();
  m.iou = shape_overlap_converged(shape, in_shape, 1e-4, &m.iou_error).iou();
  return m;
}

std::string clump_file_text(const ClumpModel& m) {
  std::ostringstream o;
  o << "# seedcal clump model (docs/clumps.md). Spheres in the body frame: centre of mass at the\n"
       "# origin, axes along the principal axes of inertia (ascending moments).\n";
  o << "format = \"seedcal-clump-1\"\n";
  o << "name = " << quoted(m.name) << "\n";
  o << "spheres_m = [\n";
  for (const auto& s : m.spheres) o << "  [" << num(s.centre_m.x()) << ", " << num(s.centre_m.y()) << ", "
                                    << num(s.centre_m.z()) << ", " << num(s.radius_m) << "],\n";
  o << "]\n\n[mass_properties]            # union of the spheres (overlaps once), adaptive octree\n";
  o << "volume_m3 = " << num(m.volume_m3) << "\n";
  o << "volume_rel_error = " << num(m.volume_rel_error) << "   # estimated bound\n";
  o << "density_kg_m3 = " << num(m.density_kg_m3) << "\n";
  o << "mass_kg = " << num(m.mass_kg) << "\n";
  o << "principal_inertia_kg_m2 = " << vec(m.principal_inertia_kg_m2) << "\n\n";
  o << "[body_frame]                 # p_shape = origin + sum_i p_body[i] * axes[i]\n";
  o << "origin_in_shape_m = " << vec(m.origin_in_shape_m) << "\n";
  o << "axes_in_shape = [" << vec(m.axes_in_shape.col(0)) << ", " << vec(m.axes_in_shape.col(1)) << ", "
    << vec(m.axes_in_shape.col(2)) << "]\n\n";
  o << "[shape]                      # the target shape; x is the length (hilum) axis\n";
  o << "kind = " << quoted(m.shape.kind) << "\n";
  if (m.shape.kind == "scan") {
    o << "path = " << quoted(m.shape.scan.path) << "\n";
    o << "unit = " << quoted(unit_name(m.shape.scan.metres_per_unit)) << "\n";
    o << "weld_m = " << num(m.shape.scan.weld_m) << "\n";
    o << "align = " << quoted(m.shape.scan.align ? "principal" : "none") << "\n";
  } else {
    const auto& e = m.shape.ellipsoid;
    o << "length_m = " << num(e.length_m) << "\nwidth_m = " << num(e.width_m) << "\nthickness_m = "
      << num(e.thickness_m) << "\nhilum_radius_m = " << num(e.hilum_radius_m) << "\nhilum_centre = "
      << num(e.hilum_centre) << "\n";
  }
  o << "volume_m3 = " << num(m.target_volume_m3) << "\n\n";
  o << "[fill]\nmethod = " << quoted(m.method) << "\n";
  o << "spheres = " << m.spheres.size() << "\n";
  if (m.requested_spheres > 0) o << "requested_spheres = " << m.requested_spheres << "\n";
  if (m.smoothness >= 0) o << "smoothness = " << num(m.smoothness) << "\n";
  if (m.min_radius_m > 0) o << "min_radius_m = " << num(m.min_radius_m) << "\n";
  o << "iou = " << num(m.iou) << "   # intersection over union with the shape\n";
  o << "iou_error = " << num(m.iou_error) << "\n";
  if (!m.layout.empty()) o << "layout = " << quoted(m.layout) << "\n";
  o << "\n[provenance]\nseedcal_version = " << quoted(m.seedcal_version) << "\n";
  o << "command = " << quoted(m.command) << "\n";
  if (!m.variety.empty()) o << "variety = " << quoted(m.variety) << "\nvariety_file = " << quoted(m.variety_file) << "\n";
  o << "soak_hours = " << num(m.soak_hours) << "\n";
  return o.str();
}

void write_clump_file(const std::string& path, const ClumpModel& m) {
  write_file_atomic(path, clump_file_text(m));
}

ClumpModel read_clump_file(const std::string& path) {
  const toml::value doc = TomlReader::parse_file(path);
  auto diag = std::make_shared<ConfigDiagnostics>();
  diag->file = path;
  TomlReader r(doc, "", diag);
  ClumpModel m;
  r.choice("format", {"seedcal-clump-1"});
  m.name = r.string("name", "");
  for (const auto& row : r.number_rows("spheres_m", 4, 1, 100000)) {
    if (!(row[3] > 0.0)) r.error("spheres_m", "every radius (4th number) must be > 0");
    m.spheres.push_back({Vec3(row[0], row[1], row[2]), row[3]});
  }
  if (auto t = r.table("mass_properties")) {
    m.volume_m3 = t->number("volume_m3", Range::positive());
    m.volume_rel_error = t->number("volume_rel_error", Range::non_negative(), 0.0);
    m.density_kg_m3 = t->number("density_kg_m3", Range::positive());
    m.mass_kg = t->number("mass_kg", Range::positive());
    if (auto v = t->vec3("principal_inertia_kg_m2", Range::positive(), true)) m.principal_inertia_kg_m2 = *v;
    t->check_unknown_keys();
  } else {
    r.error("mass_properties", "is required");
  }
  if (auto t = r.table("body_frame")) {
    if (auto v = t->vec3("origin_in_shape_m", Range{}, true)) m.origin_in_shape_m = *v;
    const auto rows = t->number_rows("axes_in_shape", 3, 3, 3);
    if (rows.size() == 3)
      for (int i = 0; i < 3; ++i) m.axes_in_shape.col(i) = Vec3(rows[i][0], rows[i][1], rows[i][2]);
    if (std::abs(m.axes_in_shape.determinant() - 1.0) > 1e-6 ||
        (m.axes_in_shape.transpose() * m.axes_in_shape - Mat3::Identity()).norm() > 1e-6)
      t->error("axes_in_shape", "must be a rotation (orthonormal rows, determinant +1)");
    t->check_unknown_keys();
  }
  if (auto t = r.table("shape")) {
    m.shape.kind = t->choice("kind", {"ellipsoid", "scan", "stl"});
    if (m.shape.kind != "ellipsoid") {
      ScanSpec& scan = m.shape.scan;
      // A relative path names a file beside the clump file; an older file's path that only exists
      // from the working directory is still found there.
      scan.path = t->string("path");
      const std::filesystem::path beside = std::filesystem::path(path).parent_path() / scan.path;
      if (std::filesystem::path(scan.path).is_relative() && std::filesystem::exists(beside) &&
          !std::filesystem::path(path).parent_path().empty())
        scan.path = beside.string();
      if (m.shape.kind == "scan") {
        scan.metres_per_unit = metres_per_unit(t->choice("unit", {"m", "mm"}));
        scan.weld_m = t->number("weld_m", Range::closed(0.0, 1e-3), 0.0);
        scan.align = t->choice("align", {"principal", "none"}) == "principal";
      }
      m.shape.kind = "scan";
    } else {
      auto& e = m.shape.ellipsoid;
      e.length_m = t->number("length_m", Range::left_open(0, 0.5));
      e.width_m = t->number("width_m", Range::left_open(0, 0.5));
      e.thickness_m = t->number("thickness_m", Range::left_open(0, 0.5));
      e.hilum_radius_m = t->number("hilum_radius_m", Range::closed(0, 0.1), 0.0);
      e.hilum_centre = t->number("hilum_centre", Range::closed(0, 1), 0.85);
    }
    m.target_volume_m3 = t->number("volume_m3", Range::positive(), 0.0);
    t->check_unknown_keys();
  }
  if (auto t = r.table("fill")) {
    m.method = t->choice("method", {"manual", "auto", "imported"});
    t->integer("spheres", 1, 100000, 0);
    m.requested_spheres = static_cast<int>(t->integer("requested_spheres", 1, 100000, 0));
    m.smoothness = t->number("smoothness", Range::closed(0, 5), -1.0);
    m.min_radius_m = t->number("min_radius_m", Range::non_negative(), 0.0);
    m.iou = t->number("iou", Range::closed(0, 1), 0.0);
    m.iou_error = t->number("iou_error", Range::non_negative(), 0.0);
    m.layout = t->string("layout", "");
    t->check_unknown_keys();
  }
  if (auto t = r.table("provenance")) {
    m.seedcal_version = t->string("seedcal_version", "");
    m.command = t->string("command", "");
    m.variety = t->string("variety", "");
    m.variety_file = t->string("variety_file", "");
    m.soak_hours = t->number("soak_hours", Range::non_negative(), 0.0);
    t->check_unknown_keys();
  }
  r.check_unknown_keys();
  diag->throw_if_any();
  return m;
}

}  // namespace seedcal
