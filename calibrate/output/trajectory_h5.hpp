#pragma once
// A scene run's trajectory: DIR/trajectory.h5 with one group per frame, and DIR/trajectory.xdmf,
// an XDMF 3 temporal collection into it that ParaView opens (docs/scenes/README.md, "Trajectories";
// scripts/paraview_open.py draws a run).
//
// trajectory.h5 (format "seedcal trajectory 2")
//   /                 attributes format, seedcal_version, scene, config_file, config (the effective
//                     TOML), seed, threads, frame_interval_s
//   /frames/NNNNNN    one per frame, numbered from 000000; attributes time_s, step; datasets
//     position_m      N x 3 float64, sphere centres
//     radius_m        N float64
//     body_id         N int32, the id of the body a sphere belongs to (stable over the run)
//     velocity_m_s    N x 3 float64, velocity of the sphere centre: v_body + w x (x_sphere - x_body)
//     speed_m_s       N float64, its magnitude
//     orientation_wxyz N x 4 float64, the unit quaternion (w, x, y, z) that turns the sphere's body
//                     from its principal frame to the world (solver/core/body_state.hpp), in the
//                     order ParaView's 3D Glyphs representation reads in its orientation mode
//                     Quaternion; the spheres of a body share it
//     vertex_index    N int32, 0 .. N-1: the XDMF's Polyvertex connectivity
//     wall_name       W strings ("name (shape)"), wall_origin_m W x 3, wall_orientation_wxyz W x 4:
//                     the walls' poses
//     wall_vertex_m   V x 3 float64, the walls' surfaces (solver/walls/wall_surface.hpp) in world
//                     coordinates at this frame's poses, so a moving wall moves from frame to frame
//     wall_triangle   T x 3 int32, indices into wall_vertex_m; written with every frame (a plane's
//                     patch follows the spheres), so each frame's group stands alone
//     wall_index      T int32, the wall (index into wall_name) each triangle belongs to
// N may change from frame to frame (seeds removed); a frame without spheres is not written.
// Format 1 had neither velocity_m_s, orientation_wxyz nor the wall surface; its other datasets are
// unchanged.
//
// trajectory.xdmf: per frame (time_s) a spatial collection of two grids, "spheres" (Polyvertex on
// position_m, point data radius_m, body_id, speed_m_s, velocity_m_s as a Vector, orientation_wxyz
// as a 4-component Matrix) and "walls" (Triangle on wall_vertex_m, cell data wall_index); a frame
// without walls has only "spheres".
#include <cstdint>
#include <string>
#include <vector>

#include "solver/sim/simulation.hpp"
#include "solver/walls/wall_surface.hpp"
#include "store/hdf5_handle.hpp"

namespace seedcal {

struct TrajectoryFrame {
  double time_s = 0.0;
  std::uint64_t step = 0;
  std::vector<Vec3> position_m;
  std::vector<double> radius_m;
  std::vector<std::int32_t> body_id;
  std::vector<Vec3> velocity_m_s;
  std::vector<double> speed_m_s;
  std::vector<Quat> orientation;  // of each sphere's body
  std::vector<std::string> wall_name;
  std::vector<Vec3> wall_origin_m;
  std::vector<Quat> wall_orientation;
  SurfaceMesh wall_surface;              // world frame
  std::vector<std::int32_t> wall_index;  // per triangle of wall_surface
};

// The frame of a simulation's current state. Circles are drawn with `segments` vertices, planes
// as a patch over the spheres' bounding box (solver/walls/wall_surface.hpp).
TrajectoryFrame trajectory_frame(const Simulation& sim, int segments = 64);

// The root attributes: what the run's metrics.json records in its provenance.
struct TrajectoryProvenance {
  std::string seedcal_version;
  std::string scene;        // kind
  std::string config_file;
  std::string config_toml;  // the effective config, overrides applied
  std::uint64_t seed = 0;
  int threads = 1;
};

class TrajectoryWriter {
 public:
  static constexpr const char* kH5Name = "trajectory.h5";
  static constexpr const char* kXdmfName = "trajectory.xdmf";

  // Nothing is written until the first frame, so a run refused before it starts leaves no file.
  TrajectoryWriter(std::string dir, TrajectoryProvenance provenance, double interval_s);
  TrajectoryWriter(const TrajectoryWriter&) = delete;
  TrajectoryWriter& operator=(const TrajectoryWriter&) = delete;
  // Finishes (the XDMF of the frames written) if finish() was not called; never throws.
  ~TrajectoryWriter();

  // Adds /frames/NNNNNN and flushes the file, so a crash loses no finished frame. The first frame
  // replaces an existing trajectory.h5 and removes a trajectory.xdmf left by an earlier run.
  void write(const TrajectoryFrame& f);
  // Closes the HDF5 file and writes trajectory.xdmf (atomically) for the frames written.
  void finish();
  // An observer for SimulationOptions that writes every frame here.
  FrameObserver observer();

  std::size_t frames() const { return frames_.size(); }
  double interval_s() const { return interval_s_; }

 private:
  struct Written {
    std::string group;  // "/frames/000000"
    double time_s;
    std::size_t spheres, wall_vertices, wall_triangles;
  };
  void open_file();

  std::string dir_;
  TrajectoryProvenance provenance_;
  double interval_s_;
  h5::Handle file_;  // open from the first frame until finish()
  std::vector<Written> frames_;
  bool finished_ = false;
};

}  // namespace seedcal
