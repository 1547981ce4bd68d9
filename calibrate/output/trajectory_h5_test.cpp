// The trajectory writer: frames of changing size read back through the HDF5 C API, and an XDMF
// whose every DataItem names a dataset of trajectory.h5 with the dimensions it has: per frame a
// spatial collection of the spheres and (when the frame has walls) the walls' triangles.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <regex>
#include <sstream>

#include "calibrate/output/trajectory_h5.hpp"
#include "tests/support/cli.hpp"

namespace seedcal {
namespace {

// Frame k: n spheres, sphere i of body 10 + i at (i, k, 0.5 i) mm, radius (1 + i) mm, velocity
// (k, i / 10, 0) m/s, orientation a turn of i / 10 rad about z; one wall, a plate lowered k mm
// (a 2-triangle patch), except in frame 3, which has none.
TrajectoryFrame make_frame(int k, std::size_t n) {
  TrajectoryFrame f;
  f.time_s = 0.01 * k;
  f.step = 1000u * static_cast<unsigned>(k);
  for (std::size_t i = 0; i < n; ++i) {
    const double x = static_cast<double>(i);
    f.position_m.push_back(1e-3 * Vec3(x, k, 0.5 * x));
    f.radius_m.push_back(1e-3 * (1.0 + x));
    f.body_id.push_back(10 + static_cast<std::int32_t>(i));
    f.velocity_m_s.emplace_back(k, 0.1 * x, 0.0);
    f.speed_m_s.push_back(f.velocity_m_s.back().norm());
    f.orientation.emplace_back(Eigen::AngleAxisd(0.1 * x, Vec3::UnitZ()));
  }
  if (k == 3) return f;
  f.wall_name = {"plate (plane)"};
  f.wall_origin_m = {Vec3(0.0, 0.0, -0.001 * k)};
  f.wall_orientation = {Quat::Identity()};
  f.wall_surface.append(tessellate(PlaneShape(Vec3::UnitZ()), Vec3::Zero(), 0.01), f.wall_origin_m[0]);
  f.wall_index.assign(f.wall_surface.triangle.size(), 0);
  return f;
}

std::vector<hsize_t> dims_of(hid_t file, const std::string& path) {
  h5::Handle set(H5Dopen2(file, path.c_str(), H5P_DEFAULT), H5Dclose, "open " + path);
  h5::Handle space(H5Dget_space(set), H5Sclose, "space of " + path);
  std::vector<hsize_t> d(static_cast<std::size_t>(H5Sget_simple_extent_ndims(space)));
  H5Sget_simple_extent_dims(space, d.data(), nullptr);
  return d;
}

template <class T>
std::vector<T> read_all(hid_t file, const std::string& path, hid_t mem_type) {
  h5::Handle set(H5Dopen2(file, path.c_str(), H5P_DEFAULT), H5Dclose, "open " + path);
  h5::Handle space(H5Dget_space(set), H5Sclose, "space of " + path);
  std::vector<T> v(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)));
  h5::check(H5Dread(set, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), "read " + path);
  return v;
}

template <class T>
T read_attr(hid_t obj, const char* name, hid_t mem_type) {
  h5::Handle a(H5Aopen(obj, name, H5P_DEFAULT), H5Aclose, std::string("open ") + name);
  T v{};
  h5::check(H5Aread(a, mem_type, &v), std::string("read ") + name);
  return v;
}

struct Written {
  std::string dir;
  std::vector<std::size_t> sizes = {4, 2, 3};
};

// Frames of 4, 2 (two bodies removed), 0 (skipped) and 3 spheres.
Written write_sample(const std::string& name) {
  Written w;
  w.dir = testing::scratch_dir(name);
  TrajectoryWriter writer(w.dir, {"0.0.0 (test)", "free_drop", "scene.toml", "kind = \"free_drop\"\n", 7, 2},
                          0.01);
  writer.write(make_frame(0, 4));
  writer.write(make_frame(1, 2));
  writer.write(make_frame(2, 0));
  writer.write(make_frame(3, 3));
  EXPECT_EQ(writer.frames(), 3u);
  writer.finish();
  return w;
}

TEST(TrajectoryH5, FramesReadBackWithTheirOwnSizes) {
  const Written w = write_sample("traj-h5");
  h5::Handle f(H5Fopen((w.dir + "/trajectory.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, "open");
  EXPECT_EQ(h5::read_string_attr(f, "format"), "seedcal trajectory 2");
  EXPECT_EQ(h5::read_string_attr(f, "seedcal_version"), "0.0.0 (test)");
  EXPECT_EQ(h5::read_string_attr(f, "scene"), "free_drop");
  EXPECT_EQ(h5::read_string_attr(f, "config_file"), "scene.toml");
  EXPECT_EQ(read_attr<std::uint64_t>(f, "seed", H5T_NATIVE_UINT64), 7u);
  EXPECT_EQ(read_attr<int>(f, "threads", H5T_NATIVE_INT), 2);
  EXPECT_EQ(read_attr<double>(f, "frame_interval_s", H5T_NATIVE_DOUBLE), 0.01);
  h5::Handle frames(H5Gopen2(f, "frames", H5P_DEFAULT), H5Gclose, "open /frames");
  H5G_info_t info;
  h5::check(H5Gget_info(frames, &info), "info");
  EXPECT_EQ(info.nlinks, 3u);
  const int source_frame[] = {0, 1, 3};  // the empty frame 2 was not written
  for (std::size_t k = 0; k < 3; ++k) {
    char g[32];
    std::snprintf(g, sizeof g, "/frames/%06zu", k);
    const std::string G = g;
    const std::size_t n = w.sizes[k];
    const TrajectoryFrame want = make_frame(source_frame[k], n);
    h5::Handle grp(H5Gopen2(f, g, H5P_DEFAULT), H5Gclose, G);
    EXPECT_EQ(read_attr<double>(grp, "time_s", H5T_NATIVE_DOUBLE), want.time_s);
    EXPECT_EQ(read_attr<std::uint64_t>(grp, "step", H5T_NATIVE_UINT64), want.step);
    EXPECT_EQ(dims_of(f, G + "/position_m"), (std::vector<hsize_t>{n, 3}));
    EXPECT_EQ(dims_of(f, G + "/radius_m"), (std::vector<hsize_t>{n}));
    const auto pos = read_all<double>(f, G + "/position_m", H5T_NATIVE_DOUBLE);
    const auto rad = read_all<double>(f, G + "/radius_m", H5T_NATIVE_DOUBLE);
    const auto ids = read_all<std::int32_t>(f, G + "/body_id", H5T_NATIVE_INT32);
    const auto speed = read_all<double>(f, G + "/speed_m_s", H5T_NATIVE_DOUBLE);
    const auto vertex = read_all<std::int32_t>(f, G + "/vertex_index", H5T_NATIVE_INT32);
    ASSERT_EQ(ids.size(), n);
    ASSERT_EQ(vertex.size(), n);
    for (std::size_t i = 0; i < n; ++i) {
      for (int c = 0; c < 3; ++c) EXPECT_EQ(pos[3 * i + static_cast<std::size_t>(c)], want.position_m[i][c]);
      EXPECT_EQ(rad[i], want.radius_m[i]);
      EXPECT_EQ(ids[i], want.body_id[i]);
      EXPECT_EQ(speed[i], want.speed_m_s[i]);
      EXPECT_EQ(vertex[i], static_cast<std::int32_t>(i));
    }
    const auto vel = read_all<double>(f, G + "/velocity_m_s", H5T_NATIVE_DOUBLE);
    const auto quat = read_all<double>(f, G + "/orientation_wxyz", H5T_NATIVE_DOUBLE);
    EXPECT_EQ(dims_of(f, G + "/velocity_m_s"), (std::vector<hsize_t>{n, 3}));
    EXPECT_EQ(dims_of(f, G + "/orientation_wxyz"), (std::vector<hsize_t>{n, 4}));
    for (std::size_t i = 0; i < n; ++i) {
      for (int c = 0; c < 3; ++c) EXPECT_EQ(vel[3 * i + static_cast<std::size_t>(c)], want.velocity_m_s[i][c]);
      const Quat& q = want.orientation[i];
      EXPECT_EQ((std::vector<double>(quat.begin() + static_cast<std::ptrdiff_t>(4 * i),
                                     quat.begin() + static_cast<std::ptrdiff_t>(4 * i + 4))),
                (std::vector<double>{q.w(), q.x(), q.y(), q.z()}));
    }
    const std::size_t walls = want.wall_name.size();
    EXPECT_EQ(h5::read_strings(grp, "wall_name"), want.wall_name);
    EXPECT_EQ(dims_of(f, G + "/wall_origin_m"), (std::vector<hsize_t>{walls, 3}));
    const std::size_t v = want.wall_surface.vertex_m.size(), t = want.wall_surface.triangle.size();
    EXPECT_EQ(dims_of(f, G + "/wall_vertex_m"), (std::vector<hsize_t>{v, 3}));
    EXPECT_EQ(dims_of(f, G + "/wall_triangle"), (std::vector<hsize_t>{t, 3}));
    EXPECT_EQ(dims_of(f, G + "/wall_index"), (std::vector<hsize_t>{t}));
    if (walls == 0) continue;
    EXPECT_EQ(read_all<double>(f, G + "/wall_origin_m", H5T_NATIVE_DOUBLE),
              (std::vector<double>{0.0, 0.0, -0.001 * source_frame[k]}));
    EXPECT_EQ(read_all<double>(f, G + "/wall_orientation_wxyz", H5T_NATIVE_DOUBLE),
              (std::vector<double>{1.0, 0.0, 0.0, 0.0}));
    const auto verts = read_all<double>(f, G + "/wall_vertex_m", H5T_NATIVE_DOUBLE);
    for (std::size_t j = 0; j < v; ++j)  // the patch in world coordinates: at the plate's height
      EXPECT_EQ(verts[3 * j + 2], -0.001 * source_frame[k]);
    const auto tris = read_all<std::int32_t>(f, G + "/wall_triangle", H5T_NATIVE_INT32);
    for (std::size_t j = 0; j < t; ++j)
      for (std::size_t c = 0; c < 3; ++c) EXPECT_EQ(tris[3 * j + c], want.wall_surface.triangle[j][c]);
    EXPECT_EQ(read_all<std::int32_t>(f, G + "/wall_index", H5T_NATIVE_INT32), want.wall_index);
  }
}

// Every DataItem of the XDMF, "file:/path" -> "Dimensions".
std::multimap<std::string, std::string> data_items(const std::string& xdmf) {
  std::multimap<std::string, std::string> out;
  const std::regex item("<DataItem Dimensions=\"([0-9 ]+)\"[^>]*>([^<]+)</DataItem>");
  for (auto it = std::sregex_iterator(xdmf.begin(), xdmf.end(), item); it != std::sregex_iterator(); ++it)
    out.emplace((*it)[2], (*it)[1]);
  return out;
}

TEST(TrajectoryH5, XdmfPointsAtEveryDatasetWithItsDimensions) {
  const Written w = write_sample("traj-xdmf");
  const std::string xdmf = testing::read_text(w.dir + "/trajectory.xdmf");
  ASSERT_FALSE(xdmf.empty());
  const auto items = data_items(xdmf);
  // Spheres: connectivity, position, radius, body id, speed, velocity, orientation; walls (frames
  // 0 and 1, not the last): triangles, vertices, wall index.
  EXPECT_EQ(items.size(), 3u * 7u + 2u * 3u);
  h5::Handle f(H5Fopen((w.dir + "/trajectory.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, "open");
  for (const auto& [ref, dims] : items) {
    ASSERT_EQ(ref.rfind("trajectory.h5:", 0), 0u) << ref;
    const std::string path = ref.substr(std::string("trajectory.h5:").size());
    ASSERT_GT(H5Lexists(f, path.c_str(), H5P_DEFAULT), 0) << path;
    std::string have;
    for (hsize_t d : dims_of(f, path)) have += (have.empty() ? "" : " ") + std::to_string(d);
    EXPECT_EQ(have, dims) << path;
  }
  for (const char* t : {"<Time Value=\"0\"/>", "<Time Value=\"0.01\"/>", "<Time Value=\"0.03\"/>",
                        "NumberOfElements=\"4\"", "NumberOfElements=\"2\"", "NumberOfElements=\"3\""})
    EXPECT_NE(xdmf.find(t), std::string::npos) << t;
  EXPECT_EQ(xdmf.find("<Time Value=\"0.02\"/>"), std::string::npos);  // the empty frame

  // Well-formed XML of the XDMF 3 layout, read by Python's own parser where Python is installed.
  if (testing::run_shell("python3 -c 'import xml.etree.ElementTree' 2>/dev/null").exit_code != 0)
    GTEST_SKIP() << "python3 not installed: XML well-formedness not checked";
  const std::string script =
      "import sys, xml.etree.ElementTree as E\n"
      "r = E.parse(sys.argv[1]).getroot()\n"
      "assert r.tag == 'Xdmf' and r.get('Version') == '3.0'\n"
      "c = r.find('Domain/Grid')\n"
      "assert c.get('GridType') == 'Collection' and c.get('CollectionType') == 'Temporal'\n"
      "walls = 0\n"
      "for frame in c.findall('Grid'):\n"
      "    assert frame.get('GridType') == 'Collection' and frame.get('CollectionType') == 'Spatial'\n"
      "    assert frame.find('Time') is not None\n"
      "    for g in frame.findall('Grid'):\n"
      "        n = g.find('Topology').get('NumberOfElements')\n"
      "        assert g.find('Geometry').get('GeometryType') == 'XYZ'\n"
      "        names = [a.get('Name') for a in g.findall('Attribute')]\n"
      "        if g.get('Name') == 'spheres':\n"
      "            assert g.find('Topology').get('TopologyType') == 'Polyvertex'\n"
      "            assert names == ['radius_m', 'body_id', 'speed_m_s', 'velocity_m_s', 'orientation_wxyz'], names\n"
      "            for d in g.iter('DataItem'):\n"
      "                assert d.get('Dimensions').split()[0] == n\n"
      "        else:\n"
      "            assert g.get('Name') == 'walls' and g.find('Topology').get('TopologyType') == 'Triangle'\n"
      "            assert names == ['wall_index'] and g.find('Attribute').get('Center') == 'Cell'\n"
      "            assert g.find('Topology/DataItem').get('Dimensions') == n + ' 3'\n"
      "            walls += 1\n"
      "        for d in g.iter('DataItem'):\n"
      "            print(d.text.strip(), d.get('Dimensions'))\n"
      "assert walls == 2, walls\n";
  testing::write_text(w.dir + "/check.py", script);
  const auto r = testing::run_shell("python3 " + w.dir + "/check.py " + w.dir + "/trajectory.xdmf 2>&1");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::string expected;
  for (const auto& [ref, dims] : items) expected += ref + " " + dims + "\n";
  std::vector<std::string> lines;
  std::istringstream in(r.output);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  std::sort(lines.begin(), lines.end());
  std::string got;
  for (const auto& l : lines) got += l + "\n";
  EXPECT_EQ(got, expected);  // the parser sees the same items the regex did
}

TEST(TrajectoryH5, NoFrameNoFiles) {
  const std::string dir = testing::scratch_dir("traj-none");
  {
    TrajectoryWriter writer(dir, {}, 0.01);
    writer.write(make_frame(0, 0));
  }
  EXPECT_FALSE(std::filesystem::exists(dir + "/trajectory.h5"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/trajectory.xdmf"));
}

TEST(TrajectoryH5, AnUnfinishedWriterStillWritesItsXdmf) {
  const std::string dir = testing::scratch_dir("traj-throw");
  try {
    TrajectoryWriter writer(dir, {}, 0.01);
    writer.write(make_frame(0, 2));
    throw std::runtime_error("the run stopped");
  } catch (const std::runtime_error&) {
  }
  const std::string xdmf = testing::read_text(dir + "/trajectory.xdmf");
  EXPECT_NE(xdmf.find("trajectory.h5:/frames/000000/position_m"), std::string::npos) << xdmf;
}

}  // namespace
}  // namespace seedcal
