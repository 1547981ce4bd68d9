#include "calibrate/output/trajectory_h5.hpp"

#include <charconv>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <sstream>

#include "store/atomic_file.hpp"
#include "store/errors.hpp"

namespace seedcal {
namespace {

constexpr int kFormatVersion = 2;

// Shortest text that reads back as the same double.
std::string number_text(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

template <class T>
void write_scalar_attr(hid_t obj, const char* name, T value, hid_t type) {
  h5::Handle space(H5Screate(H5S_SCALAR), H5Sclose, "create a scalar space");
  h5::Handle attr(H5Acreate2(obj, name, type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
                  std::string("create attribute ") + name);
  h5::check(H5Awrite(attr, type, &value), std::string("write attribute ") + name);
}

// A dataset of rows x cols values (cols = 0: one-dimensional), from contiguous data.
template <class T>
void write_array(hid_t group, const char* name, const T* data, std::size_t rows, std::size_t cols,
                 hid_t file_type, hid_t mem_type) {
  const hsize_t dims[2] = {rows, cols};
  h5::Handle space(H5Screate_simple(cols > 0 ? 2 : 1, dims, nullptr), H5Sclose, "create a data space");
  h5::Handle set(H5Dcreate2(group, name, file_type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                 H5Dclose, std::string("create dataset ") + name);
  if (rows > 0)
    h5::check(H5Dwrite(set, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), std::string("write ") + name);
}

void write_vec3s(hid_t group, const char* name, const std::vector<Vec3>& v) {
  std::vector<double> flat;
  flat.reserve(3 * v.size());
  for (const Vec3& p : v) flat.insert(flat.end(), {p.x(), p.y(), p.z()});
  write_array(group, name, flat.data(), v.size(), 3, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE);
}

void write_doubles(hid_t group, const char* name, const std::vector<double>& v) {
  write_array(group, name, v.data(), v.size(), 0, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE);
}

void write_quats(hid_t group, const char* name, const std::vector<Quat>& v) {
  std::vector<double> flat;
  flat.reserve(4 * v.size());
  for (const Quat& r : v) flat.insert(flat.end(), {r.w(), r.x(), r.y(), r.z()});
  write_array(group, name, flat.data(), v.size(), 4, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE);
}

// One DataItem naming a dataset of `group` in the HDF5 file.
void data_item(std::ostringstream& x, const std::string& h5, const std::string& group, const std::string& dims,
               const char* type, int precision, const char* set) {
  x << "            <DataItem Dimensions=\"" << dims << "\" NumberType=\"" << type << "\" Precision=\""
    << precision << "\" Format=\"HDF\">" << h5 << ":" << group << "/" << set << "</DataItem>\n";
}

// One grid of the temporal collection: a spatial collection of the spheres (vertices with their
// radius, body id, speed, velocity and orientation as point data) and the walls (triangles with
// each one's wall index as cell data).
void xdmf_grid(std::ostringstream& x, const std::string& h5, const std::string& group, double time_s,
               std::size_t n, std::size_t wall_vertices, std::size_t wall_triangles) {
  const std::string name = group.substr(group.rfind('/') + 1);
  const std::string count = std::to_string(n);
  auto attribute = [&](const char* set, const char* kind, const char* center, const std::string& dims,
                       const char* type, int precision) {
    x << "          <Attribute Name=\"" << set << "\" AttributeType=\"" << kind << "\" Center=\"" << center
      << "\">\n";
    data_item(x, h5, group, dims, type, precision, set);
    x << "          </Attribute>\n";
  };
  x << "      <Grid Name=\"frame_" << name << "\" GridType=\"Collection\" CollectionType=\"Spatial\">\n"
    << "        <Time Value=\"" << number_text(time_s) << "\"/>\n"
    << "        <Grid Name=\"spheres\" GridType=\"Uniform\">\n"
    << "          <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << count
    << "\" NodesPerElement=\"1\">\n";
  data_item(x, h5, group, count, "Int", 4, "vertex_index");
  x << "          </Topology>\n"
    << "          <Geometry GeometryType=\"XYZ\">\n";
  data_item(x, h5, group, count + " 3", "Float", 8, "position_m");
  x << "          </Geometry>\n";
  attribute("radius_m", "Scalar", "Node", count, "Float", 8);
  attribute("body_id", "Scalar", "Node", count, "Int", 4);
  attribute("speed_m_s", "Scalar", "Node", count, "Float", 8);
  attribute("velocity_m_s", "Vector", "Node", count + " 3", "Float", 8);
  // Four components: readers take an attribute's component count from its dimensions.
  attribute("orientation_wxyz", "Matrix", "Node", count + " 4", "Float", 8);
  x << "        </Grid>\n";
  if (wall_triangles > 0) {
    const std::string tris = std::to_string(wall_triangles);
    x << "        <Grid Name=\"walls\" GridType=\"Uniform\">\n"
      << "          <Topology TopologyType=\"Triangle\" NumberOfElements=\"" << tris
      << "\" NodesPerElement=\"3\">\n";
    data_item(x, h5, group, tris + " 3", "Int", 4, "wall_triangle");
    x << "          </Topology>\n"
      << "          <Geometry GeometryType=\"XYZ\">\n";
    data_item(x, h5, group, std::to_string(wall_vertices) + " 3", "Float", 8, "wall_vertex_m");
    x << "          </Geometry>\n";
    attribute("wall_index", "Scalar", "Cell", tris, "Int", 4);
    x << "        </Grid>\n";
  }
  x << "      </Grid>\n";
}

}  // namespace

TrajectoryFrame trajectory_frame(const Simulation& sim, int segments) {
  TrajectoryFrame f;
  f.time_s = sim.time_s();
  f.step = sim.step_count();
  const SphereState& S = sim.spheres();
  const BodyState& B = sim.bodies();
  f.position_m = S.position_m;
  f.radius_m = S.radius_m;
  f.body_id.reserve(S.size());
  f.velocity_m_s.reserve(S.size());
  f.speed_m_s.reserve(S.size());
  f.orientation.reserve(S.size());
  // The spheres' bounding box, for the planes' patches.
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (std::size_t i = 0; i < S.size(); ++i) {
    const std::uint32_t b = S.body[i];
    f.body_id.push_back(static_cast<std::int32_t>(B.id[b]));
    // Rigid body: v_sphere = v_com + w x (x_sphere - x_com).
    const Vec3 v = B.velocity_m_s[b] + B.angular_velocity[b].cross(S.position_m[i] - B.position_m[b]);
    f.velocity_m_s.push_back(v);
    f.speed_m_s.push_back(v.norm());
    f.orientation.push_back(B.orientation[b]);
    lo = lo.cwiseMin(S.position_m[i] - Vec3::Constant(S.radius_m[i]));
    hi = hi.cwiseMax(S.position_m[i] + Vec3::Constant(S.radius_m[i]));
  }
  TessellationOptions surface;
  surface.segments = segments;
  const bool boxed = S.size() > 0 && lo.allFinite() && hi.allFinite();
  const Vec3 centre = boxed ? Vec3(0.5 * (lo + hi)) : Vec3::Zero();
  // A ball holding the box: its half-diagonal (a box of one point still gets a patch).
  const double radius = boxed ? 0.5 * (hi - lo).norm() : 0.0;
  const auto walls = static_cast<std::int32_t>(sim.walls().size());
  for (std::int32_t k = 0; k < walls; ++k) {
    const Wall& w = sim.walls()[static_cast<std::size_t>(k)];
    f.wall_name.push_back(w.name + " (" + w.shape->type_name() + ")");
    f.wall_origin_m.push_back(w.pose.origin_m);
    f.wall_orientation.push_back(w.pose.orientation);
    surface.region_centre_m = w.pose.orientation.conjugate() * (centre - w.pose.origin_m);
    surface.region_radius_m = radius > 0.0 ? radius : 1.0;
    f.wall_surface.append(tessellate(*w.shape, surface), w.pose.origin_m, w.pose.orientation);
    f.wall_index.resize(f.wall_surface.triangle.size(), k);
  }
  return f;
}

TrajectoryWriter::TrajectoryWriter(std::string dir, TrajectoryProvenance provenance, double interval_s)
    : dir_(std::move(dir)), provenance_(std::move(provenance)), interval_s_(interval_s) {}

TrajectoryWriter::~TrajectoryWriter() {
  try {
    finish();
  } catch (const std::exception& e) {
    std::cerr << "seedcal: " << e.what() << "\n";
  }
}

void TrajectoryWriter::open_file() {
  const std::string path = dir_ + "/" + kH5Name;
  std::filesystem::create_directories(dir_);
  std::filesystem::remove(dir_ + "/" + kXdmfName);
  h5::QuietErrors quiet;
  try {
    file_ = h5::Handle(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose,
                       "create the file");
    h5::write_string_attr(file_, "format", "seedcal trajectory " + std::to_string(kFormatVersion));
    h5::write_string_attr(file_, "seedcal_version", provenance_.seedcal_version);
    h5::write_string_attr(file_, "scene", provenance_.scene);
    h5::write_string_attr(file_, "config_file", provenance_.config_file);
    h5::write_string_attr(file_, "config", provenance_.config_toml);
    write_scalar_attr(file_, "seed", provenance_.seed, H5T_NATIVE_UINT64);
    write_scalar_attr(file_, "threads", provenance_.threads, H5T_NATIVE_INT);
    write_scalar_attr(file_, "frame_interval_s", interval_s_, H5T_NATIVE_DOUBLE);
    h5::Handle frames(H5Gcreate2(file_, "frames", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
                      "create /frames");
  } catch (const std::exception& e) {
    throw RunFailed(path + ": " + e.what());
  }
}

void TrajectoryWriter::write(const TrajectoryFrame& f) {
  if (finished_) throw std::logic_error("TrajectoryWriter::write after finish");
  const std::size_t n = f.radius_m.size();
  if (f.position_m.size() != n || f.body_id.size() != n || f.speed_m_s.size() != n ||
      f.velocity_m_s.size() != n || f.orientation.size() != n ||
      f.wall_origin_m.size() != f.wall_name.size() || f.wall_orientation.size() != f.wall_name.size() ||
      f.wall_index.size() != f.wall_surface.triangle.size())
    throw std::invalid_argument("TrajectoryWriter::write: the frame's arrays differ in length");
  if (n == 0) return;
  if (file_.get() < 0) open_file();
  char name[32];
  std::snprintf(name, sizeof name, "/frames/%06zu", frames_.size());
  h5::QuietErrors quiet;
  try {
    h5::Handle g(H5Gcreate2(file_, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
                 std::string("create ") + name);
    write_scalar_attr(g, "time_s", f.time_s, H5T_NATIVE_DOUBLE);
    write_scalar_attr(g, "step", f.step, H5T_NATIVE_UINT64);
    write_vec3s(g, "position_m", f.position_m);
    write_doubles(g, "radius_m", f.radius_m);
    write_array(g, "body_id", f.body_id.data(), n, 0, H5T_STD_I32LE, H5T_NATIVE_INT32);
    // The Polyvertex connectivity 0 .. N-1, explicit: readers differ on generating it.
    std::vector<std::int32_t> vertex(n);
    for (std::size_t i = 0; i < n; ++i) vertex[i] = static_cast<std::int32_t>(i);
    write_array(g, "vertex_index", vertex.data(), n, 0, H5T_STD_I32LE, H5T_NATIVE_INT32);
    write_vec3s(g, "velocity_m_s", f.velocity_m_s);
    write_doubles(g, "speed_m_s", f.speed_m_s);
    write_quats(g, "orientation_wxyz", f.orientation);
    h5::write_strings(g, "wall_name", f.wall_name);
    write_vec3s(g, "wall_origin_m", f.wall_origin_m);
    write_quats(g, "wall_orientation_wxyz", f.wall_orientation);
    write_vec3s(g, "wall_vertex_m", f.wall_surface.vertex_m);
    static_assert(sizeof(std::array<std::int32_t, 3>) == 3 * sizeof(std::int32_t), "triangles are contiguous");
    write_array(g, "wall_triangle", f.wall_surface.triangle.data(), f.wall_surface.triangle.size(), 3,
                H5T_STD_I32LE, H5T_NATIVE_INT32);
    write_array(g, "wall_index", f.wall_index.data(), f.wall_index.size(), 0, H5T_STD_I32LE, H5T_NATIVE_INT32);
    h5::check(H5Fflush(file_, H5F_SCOPE_GLOBAL), "flush the file");
  } catch (const std::exception& e) {
    throw RunFailed(dir_ + "/" + kH5Name + ": " + e.what());
  }
  frames_.push_back({name, f.time_s, n, f.wall_surface.vertex_m.size(), f.wall_surface.triangle.size()});
}

void TrajectoryWriter::finish() {
  if (finished_) return;
  finished_ = true;
  if (file_.get() < 0) return;  // no frame: no files
  file_ = h5::Handle();         // closes the file
  std::ostringstream x;
  x << "<?xml version=\"1.0\" ?>\n"
    << "<!-- seedcal trajectory: open in ParaView (scripts/paraview_open.py); per frame the block \"spheres\" "
       "(a Glyph of type Sphere, scale array radius_m, scale factor 2) and the block \"walls\" -->\n"
    << "<Xdmf Version=\"3.0\">\n"
    << "  <Domain>\n"
    << "    <Grid Name=\"trajectory\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (const Written& w : frames_)
    xdmf_grid(x, kH5Name, w.group, w.time_s, w.spheres, w.wall_vertices, w.wall_triangles);
  x << "    </Grid>\n"
    << "  </Domain>\n"
    << "</Xdmf>\n";
  write_file_atomic(dir_ + "/" + kXdmfName, x.str());
}

FrameObserver TrajectoryWriter::observer() {
  FrameObserver o;
  o.interval_s = interval_s_;
  o.on_frame = [this](const Simulation& sim) { write(trajectory_frame(sim)); };
  return o;
}

}  // namespace seedcal
