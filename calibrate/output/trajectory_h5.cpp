#include "calibrate/output/trajectory_h5.hpp"

#include <charconv>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "store/atomic_file.hpp"
#include "store/errors.hpp"

namespace seedcal {
namespace {

constexpr int kFormatVersion = 1;

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

// One grid of the temporal collection: the spheres of one frame as vertices, with their radius,
// body id and speed as point data.
void xdmf_grid(std::ostringstream& x, const std::string& h5, const std::string& group, double time_s,
               std::size_t n) {
  const std::string name = group.substr(group.rfind('/') + 1);
  const std::string count = std::to_string(n);
  auto item = [&](const std::string& dims, const char* type, int precision, const char* set) {
    x << "          <DataItem Dimensions=\"" << dims << "\" NumberType=\"" << type << "\" Precision=\""
      << precision << "\" Format=\"HDF\">" << h5 << ":" << group << "/" << set << "</DataItem>\n";
  };
  auto attribute = [&](const char* set, const char* type, int precision) {
    x << "        <Attribute Name=\"" << set << "\" AttributeType=\"Scalar\" Center=\"Node\">\n";
    item(count, type, precision, set);
    x << "        </Attribute>\n";
  };
  x << "      <Grid Name=\"frame_" << name << "\" GridType=\"Uniform\">\n"
    << "        <Time Value=\"" << number_text(time_s) << "\"/>\n"
    << "        <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << count
    << "\" NodesPerElement=\"1\">\n";
  item(count, "Int", 4, "vertex_index");
  x << "        </Topology>\n"
    << "        <Geometry GeometryType=\"XYZ\">\n";
  item(count + " 3", "Float", 8, "position_m");
  x << "        </Geometry>\n";
  attribute("radius_m", "Float", 8);
  attribute("body_id", "Int", 4);
  attribute("speed_m_s", "Float", 8);
  x << "      </Grid>\n";
}

}  // namespace

TrajectoryFrame trajectory_frame(const Simulation& sim) {
  TrajectoryFrame f;
  f.time_s = sim.time_s();
  f.step = sim.step_count();
  const SphereState& S = sim.spheres();
  const BodyState& B = sim.bodies();
  f.position_m = S.position_m;
  f.radius_m = S.radius_m;
  f.body_id.reserve(S.size());
  f.speed_m_s.reserve(S.size());
  for (std::size_t i = 0; i < S.size(); ++i) {
    const std::uint32_t b = S.body[i];
    f.body_id.push_back(static_cast<std::int32_t>(B.id[b]));
    // Rigid body: v_sphere = v_com + w x (x_sphere - x_com).
    const Vec3 v = B.velocity_m_s[b] + B.angular_velocity[b].cross(S.position_m[i] - B.position_m[b]);
    f.speed_m_s.push_back(v.norm());
  }
  for (const Wall& w : sim.walls()) {
    f.wall_name.push_back(w.name + " (" + w.shape->type_name() + ")");
    f.wall_origin_m.push_back(w.pose.origin_m);
    f.wall_orientation.push_back(w.pose.orientation);
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
      f.wall_origin_m.size() != f.wall_name.size() || f.wall_orientation.size() != f.wall_name.size())
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
    write_doubles(g, "speed_m_s", f.speed_m_s);
    h5::write_strings(g, "wall_name", f.wall_name);
    write_vec3s(g, "wall_origin_m", f.wall_origin_m);
    std::vector<double> q;
    for (const Quat& r : f.wall_orientation) q.insert(q.end(), {r.w(), r.x(), r.y(), r.z()});
    write_array(g, "wall_orientation_wxyz", q.data(), f.wall_orientation.size(), 4, H5T_IEEE_F64LE,
                H5T_NATIVE_DOUBLE);
    h5::check(H5Fflush(file_, H5F_SCOPE_GLOBAL), "flush the file");
  } catch (const std::exception& e) {
    throw RunFailed(dir_ + "/" + kH5Name + ": " + e.what());
  }
  frames_.push_back({name, f.time_s, n});
}

void TrajectoryWriter::finish() {
  if (finished_) return;
  finished_ = true;
  if (file_.get() < 0) return;  // no frame: no files
  file_ = h5::Handle();         // closes the file
  std::ostringstream x;
  x << "<?xml version=\"1.0\" ?>\n"
    << "<!-- seedcal trajectory: open in ParaView; spheres as a Glyph (Sphere) scaled by radius_m -->\n"
    << "<Xdmf Version=\"3.0\">\n"
    << "  <Domain>\n"
    << "    <Grid Name=\"trajectory\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (const Written& w : frames_) xdmf_grid(x, kH5Name, w.group, w.time_s, w.spheres);
  x << "    </Grid>\n"
    << "  </Domain>\n"
    << "</Xdmf>\n";
  write_file_atomic(dir_ + "/" + kXdmfName, x.str());
}

FrameObserver TrajectoryWriter::observer() {
  return {interval_s_, [this](const Simulation& sim) { write(trajectory_frame(sim)); }};
}

}  // namespace seedcal
