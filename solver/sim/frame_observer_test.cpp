// The frame observer (SimulationOptions::observer): frames at t = 0, at each multiple of the
// interval, at a guard failure and at the end, never twice for one step; the run is bit-identical
// with and without it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "tests/support/worlds.hpp"

namespace seedcal {
namespace {

struct Frame {
  double time_s;
  std::uint64_t step;
  std::size_t spheres;
};

// Three spheres of 5 mm falling side by side onto the plane z = 0 from 2, 4 and 6 cm. E = 10 MPa:
// the Rayleigh step is 0.45 ms, so dt = 10 us is well inside it.
Simulation falling_spheres(double dt_s, const FrameObserver& observer) {
  testing::MaterialSpec m;
  m.youngs_modulus_pa = 1e7;
  SimulationOptions opt;
  opt.dt_s = dt_s;
  opt.observer = observer;
  Simulation sim(testing::make_table(m), opt);
  for (int i = 0; i < 3; ++i) {
    BodyDef b = sphere_body(0.005, m.density_kg_m3, 0);
    b.position_m = Vec3(0.02 * i, 0.0, 0.02 * (i + 1));
    sim.add_body(b);
  }
  sim.add_wall(testing::plane_wall(Vec3::Zero(), Vec3::UnitZ()));
  return sim;
}

FrameObserver recorder(double interval_s, std::vector<Frame>& frames) {
  FrameObserver o;
  o.interval_s = interval_s;
  o.on_frame = [&frames](const Simulation& s) { frames.push_back({s.time_s(), s.step_count(), s.spheres().size()}); };
  return o;
}

FrameObserver progress_recorder(double interval_s, std::vector<Frame>& calls) {
  FrameObserver o;
  o.progress_interval_s = interval_s;
  o.on_progress = [&calls](const Simulation& s) { calls.push_back({s.time_s(), s.step_count(), s.spheres().size()}); };
  return o;
}

TEST(FrameObserver, FramesAtStartEveryIntervalAndEnd) {
  std::vector<Frame> frames;
  const double dt = 1e-5, interval = 0.01;
  Simulation sim = falling_spheres(dt, recorder(interval, frames));
  // 0.0505 s: five whole intervals and half a step's worth of a sixth.
  ASSERT_TRUE(sim.run(5050)) << sim.failure().message;
  ASSERT_TRUE(sim.final_check());
  ASSERT_EQ(frames.size(), 7u);  // t = 0, 0.01, ..., 0.05 and the end
  for (std::size_t k = 0; k < 6; ++k) {
    // Each frame is the state at the first step at or after k x interval: the time summed step by
    // step lands within one step of the multiple (a relative rounding of ~1e-13 over 5000 steps).
    EXPECT_NEAR(frames[k].time_s, static_cast<double>(k) * interval, dt) << k;
    EXPECT_EQ(frames[k].step, static_cast<std::uint64_t>(std::llround(frames[k].time_s / dt))) << k;
    EXPECT_EQ(frames[k].spheres, 3u);
  }
  EXPECT_EQ(frames[0].step, 0u);
  EXPECT_EQ(frames.back().step, 5050u);
  EXPECT_NEAR(frames.back().time_s, 0.0505, 1e-12);
  // A second final_check adds nothing: the end state is already a frame.
  ASSERT_TRUE(sim.final_check());
  EXPECT_EQ(frames.size(), 7u);
}

TEST(FrameObserver, RemovedBodiesLeaveLaterFrames) {
  std::vector<Frame> frames;
  Simulation sim = falling_spheres(1e-5, recorder(0.001, frames));
  ASSERT_TRUE(sim.run(1000));
  sim.remove_bodies([&](std::uint32_t b) { return sim.bodies().id[b] == 2; });
  ASSERT_TRUE(sim.run(1000));
  ASSERT_TRUE(sim.final_check());
  ASSERT_EQ(frames.size(), 21u);  // t = 0, 1, ..., 20 ms (the last one from final_check)
  EXPECT_EQ(frames[10].spheres, 2u);  // t = 10 ms: taken after the removal
  EXPECT_EQ(frames[9].spheres, 3u);
  EXPECT_EQ(frames.back().spheres, 2u);
}

TEST(FrameObserver, DoesNotChangeTheRun) {
  std::vector<Frame> frames;
  Simulation observed = falling_spheres(1e-5, recorder(1e-3, frames));
  Simulation plain = falling_spheres(1e-5, {});
  // 0.1 s: the lowest sphere (15 mm gap) hits the plane at 55 ms and is rising again.
  ASSERT_TRUE(observed.run(10000));
  ASSERT_TRUE(plain.run(10000));
  EXPECT_EQ(frames.size(), 100u);  // t = 0, 1, ..., 99 ms
  EXPECT_GT(plain.bodies().velocity_m_s[0].z(), 0.0);  // free fall would be -0.98 m/s
  const auto& a = observed.bodies().position_m;
  const auto& b = plain.bodies().position_m;
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec3)), 0);
}

TEST(FrameObserver, TakesTheStateAGuardStoppedAt) {
  std::vector<Frame> frames;
  Simulation sim = falling_spheres(1e-5, recorder(1.0, frames));
  sim.bodies().velocity_m_s[0] = Vec3(std::nan(""), 0.0, 0.0);
  EXPECT_FALSE(sim.run(10));
  ASSERT_EQ(frames.size(), 2u);  // t = 0 and the failing step
  EXPECT_EQ(frames[1].step, 1u);
  EXPECT_FALSE(sim.final_check());
  EXPECT_EQ(frames.size(), 2u);
}

// Progress calls come every interval of simulated time (the first after one interval), never at the
// end or on a failure, and leave the run's bits alone.
TEST(FrameObserver, ProgressEveryIntervalWithoutChangingTheRun) {
  std::vector<Frame> calls;
  const double dt = 1e-5, interval = 0.002;
  Simulation observed = falling_spheres(dt, progress_recorder(interval, calls));
  Simulation plain = falling_spheres(dt, {});
  ASSERT_TRUE(observed.run(10000));
  ASSERT_TRUE(plain.run(10000));
  ASSERT_TRUE(observed.final_check());
  // t = 2, 4, ..., 98 ms: each at the first step at or after the previous call plus the interval,
  // so at most one step late each time (49 calls, or 48 if the late steps add up to an interval).
  ASSERT_GE(calls.size(), 48u);
  ASSERT_LE(calls.size(), 49u);
  for (std::size_t k = 1; k < calls.size(); ++k) {
    EXPECT_GE(calls[k].time_s - calls[k - 1].time_s, interval - 1e-12) << k;
    EXPECT_LE(calls[k].time_s - calls[k - 1].time_s, interval + dt + 1e-12) << k;
  }
  const auto& a = observed.bodies().position_m;
  const auto& b = plain.bodies().position_m;
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec3)), 0);
  std::vector<Frame> none;
  EXPECT_THROW(falling_spheres(dt, progress_recorder(0.0, none)), std::invalid_argument);
}

TEST(FrameObserver, NeedsAPositiveInterval) {
  std::vector<Frame> frames;
  EXPECT_THROW(falling_spheres(1e-5, recorder(0.0, frames)), std::invalid_argument);
}

}  // namespace
}  // namespace seedcal
