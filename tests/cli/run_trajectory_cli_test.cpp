// End-to-end: `seedcal run` writes a trajectory on request ([output] trajectory = true, here by
// --set): trajectory.h5 with the run's provenance and one frame per interval, trajectory.xdmf
// naming each frame, with the walls drawn where they are in each frame; none unless asked; bad
// [output] values exit 2 naming the key and the range.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <regex>

#include "store/hdf5_handle.hpp"
#include "tests/support/cli.hpp"

namespace seedcal {
namespace {

using testing::run_cli;

// A Python with h5py (scripts/setup.sh installs python3-h5py for the system's python3): the one
// CMake found, else the system's, else the first on PATH.
std::string python_with_h5py() {
  std::vector<std::string> candidates;
  if (const char* p = std::getenv("SEEDCAL_PYTHON")) candidates.emplace_back(p);
  candidates.insert(candidates.end(), {"/usr/bin/python3", "python3"});
  for (const auto& py : candidates)
    if (testing::run_shell(py + " -c 'import h5py, numpy' > /dev/null 2>&1").exit_code == 0) return py;
  return "";
}

// One seed (nine spheres) dropped 150 mm: about 0.3 s simulated, a second of CPU.
std::string free_drop() {
  return testing::source_dir() + "/data/scenes/jinong1/free_drop.toml --set repeats=1 --set fidelity=quick";
}

TEST(RunTrajectoryCli, FreeDropWritesFramesAtTheInterval) {
  const std::string out = testing::scratch_dir("traj-free-drop");
  const auto r = run_cli("run " + free_drop() + " --out " + out +
                         " --seed 5 --set output.trajectory=true --set output.trajectory_interval_s=0.02");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto j = nlohmann::json::parse(testing::read_text(out + "/metrics.json"));
  ASSERT_TRUE(j.contains("trajectory")) << j.dump(2);
  EXPECT_EQ(j["trajectory"]["h5"], "trajectory.h5");
  EXPECT_EQ(j["trajectory"]["xdmf"], "trajectory.xdmf");
  EXPECT_EQ(j["trajectory"]["interval_s"], 0.02);
  // A frame at t = 0, one per 20 ms and the last state: steps x dt / interval + 1 or + 2 (the end
  // may fall on a frame time).
  const double t_end = j["steps"].get<double>() * j["dt_s"].get<double>();
  const auto frames = j["trajectory"]["frames"].get<std::size_t>();
  const auto whole = static_cast<std::size_t>(t_end / 0.02);
  EXPECT_GE(frames, whole + 1) << t_end;
  EXPECT_LE(frames, whole + 2) << t_end;

  h5::Handle f(H5Fopen((out + "/trajectory.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, "open");
  EXPECT_EQ(h5::read_string_attr(f, "scene"), "free_drop");
  EXPECT_NE(h5::read_string_attr(f, "config").find("trajectory"), std::string::npos);
  h5::Handle seed(H5Aopen(f, "seed", H5P_DEFAULT), H5Aclose, "open seed");
  std::uint64_t s = 0;
  h5::check(H5Aread(seed, H5T_NATIVE_UINT64, &s), "read seed");
  EXPECT_EQ(s, 5u);
  h5::Handle g(H5Gopen2(f, "frames", H5P_DEFAULT), H5Gclose, "open /frames");
  H5G_info_t info;
  h5::check(H5Gget_info(g, &info), "info");
  EXPECT_EQ(info.nlinks, frames);

  // One grid per frame, each of the clump's nine spheres.
  const std::string xdmf = testing::read_text(out + "/trajectory.xdmf");
  const std::regex grid("<Grid Name=\"frame_[0-9]{6}\"");
  EXPECT_EQ(static_cast<std::size_t>(std::distance(std::sregex_iterator(xdmf.begin(), xdmf.end(), grid),
                                                   std::sregex_iterator())),
            frames);
  const std::regex nine("NumberOfElements=\"9\"");
  EXPECT_EQ(static_cast<std::size_t>(std::distance(std::sregex_iterator(xdmf.begin(), xdmf.end(), nine),
                                                   std::sregex_iterator())),
            frames);
}

// The direct shear miniature of tests/cli/scenes_mini_test.cpp (9 seeds in a 30 mm box, the
// servo-controlled lid, the upper ring sheared 1 mm): tests/scripts/trajectory_xdmf_check.py reads
// trajectory.xdmf back as a reader would, finds every DataItem in trajectory.h5 with its declared
// dimensions, the upper ring (sheared) and the lid (servo-controlled, in from the end of the pour)
// at other vertices in the last frame than in their first, the lower ring (fixed) at the same.
TEST(RunTrajectoryCli, TheXdmfDrawsTheWallsWhereTheyAre) {
  const std::string py = python_with_h5py();
  ASSERT_FALSE(py.empty()) << "no python3 with h5py: install python3-h5py (scripts/setup.sh)";
  const std::string out = testing::scratch_dir("traj-shear");
  const auto r = run_cli("run " + testing::source_dir() +
                         "/data/scenes/jinong1/direct_shear.toml --set fidelity=quick --seed 1 --threads 1 --out " +
                         out +
                         " --set direct_shear.quick.diameter_m=0.03 --set direct_shear.quick.sample_height_m=0.012"
                         " --set direct_shear.quick.shear_displacement_m=0.001"
                         " --set direct_shear.quick.shear_speed_m_s=0.05"
                         " --set output.trajectory=true --set output.trajectory_interval_s=0.01");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto check = testing::run_shell(py + " " + testing::source_dir() + "/tests/scripts/trajectory_xdmf_check.py " +
                                        out + " --moving upper_ring --moving lid --still lower_ring 2>&1");
  EXPECT_EQ(check.exit_code, 0) << check.output;
  EXPECT_NE(check.output.find("upper_ring: "), std::string::npos) << check.output;
  std::filesystem::remove_all(out);
}

TEST(RunTrajectoryCli, NoTrajectoryUnlessAsked) {
  const std::string out = testing::scratch_dir("traj-none");
  const auto r = run_cli("run " + free_drop() + " --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_FALSE(std::filesystem::exists(out + "/trajectory.h5"));
  EXPECT_FALSE(std::filesystem::exists(out + "/trajectory.xdmf"));
  const auto j = nlohmann::json::parse(testing::read_text(out + "/metrics.json"));
  EXPECT_FALSE(j.contains("trajectory"));
}

TEST(RunTrajectoryCli, BadOutputKeysExitTwo) {
  const std::string out = testing::scratch_dir("traj-bad");
  const auto r = run_cli("run " + free_drop() + " --out " + out +
                         " --set output.trajectory=true --set output.trajectory_interval_s=-1");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("free_drop.toml"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("output.trajectory_interval_s = -1: must be in (0, 1000]"), std::string::npos)
      << r.output;
  EXPECT_FALSE(std::filesystem::exists(out + "/trajectory.h5"));  // refused before it ran

  const auto u = run_cli("run " + free_drop() + " --out " + out + " --set output.trajectry=true");
  EXPECT_EQ(u.exit_code, 2) << u.output;
  EXPECT_NE(u.output.find("did you mean \"trajectory\""), std::string::npos) << u.output;

  const auto b = run_cli("run " + free_drop() + " --out " + out + " --set output.trajectory=3");
  EXPECT_EQ(b.exit_code, 2) << b.output;
  EXPECT_NE(b.output.find("output.trajectory"), std::string::npos) << b.output;
}

}  // namespace
}  // namespace seedcal
