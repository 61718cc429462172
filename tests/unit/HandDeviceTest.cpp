// HandDevice: the simulated hand follows its trajectory, and with the default
// parameters it comes to rest against a surface under every renderer (no
// growing oscillation), closed loop at 1 kHz.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include <glm/geometric.hpp>

#include "measure/Renderers.h"
#include "millsim/devices/HandDevice.h"
#include "millsim/renderers/LineProxyRenderer.h"
#include "millsim/renderers/SurfacePointRenderer.h"
#include "millsim/run/HapticLoop.h"
#include "millsim/volume/VoxelScene.h"
#include "millsim/volume/VoxelVolume.h"
#include "AnalyticScenes.h"

using namespace millsim;
using namespace millsim::test;

namespace {

Trajectory line(glm::dvec3 from, glm::dvec3 to, double seconds, double hold) {
  return Trajectory({{0.0, Pose{from, glm::dquat(1, 0, 0, 0)}, false},
                     {seconds, Pose{to, glm::dquat(1, 0, 0, 0)}, false},
                     {seconds + hold, Pose{to, glm::dquat(1, 0, 0, 0)}, false}});
}

struct Trace {
  std::vector<glm::dvec3> positions;
  std::vector<double> forces;
};

Trace runClosedLoop(VoxelScene& scene, std::unique_ptr<HapticAlgorithm> algorithm, const Trajectory& t,
                  const HandModel& hand, double seconds) {
  LoopSettings s;
  s.timing = false;
  s.logCapacity = 4;
  HapticLoop loop(scene, std::move(algorithm), makeHandDriver(t, hand, false), s);
  Trace run;
  for (long n = 0; n < long(seconds * 1000); ++n) {
    loop.stepSimulated();
    loop.records().drain([&](const FrameRecord& r) {
      run.positions.push_back(r.device.position);
      run.forces.push_back(glm::length(r.force));
    });
  }
  return run;
}

// Peak-to-peak of y over frames [a, b).
double spread(const Trace& r, std::size_t a, std::size_t b) {
  double lo = 1e9, hi = -1e9;
  for (std::size_t i = a; i < b; ++i) {
    lo = std::min(lo, r.positions[i].y);
    hi = std::max(hi, r.positions[i].y);
  }
  return hi - lo;
}

}  // namespace

TEST(HandDevice, FollowsItsTrajectoryInFreeSpace) {
  VoxelScene empty;
  SurfacePointRenderer renderer;
  const Trajectory t = line({0, 0.02, 0}, {0.01, 0.02, 0}, 1.0, 1.0);
  const Trace r = runClosedLoop(empty, renderer.compile(kTool, empty), t, HandModel{}, 2.0);
  // Lags while moving at 10 mm/s, arrives when the reference stops.
  EXPECT_GT(glm::length(r.positions[500] - t.at(0.5).pose.position), 1e-6);
  EXPECT_LT(glm::length(r.positions[1999] - glm::dvec3(0.01, 0.02, 0)), 20e-6);
}

TEST(HandDevice, ComesToRestPressingOnASurfaceWithEveryRenderer) {
  // The hand aims 1 mm below the surface: the renderer must hold it there.
  const Trajectory t = line({0, 2e-3, 0}, {0, -1e-3 + 0.0, 0}, 0.5, 3.0);
  // Every renderer type in the registry, plugins included.
  const std::vector<std::string> types = measure::registeredRenderers();
  ASSERT_GE(types.size(), 3u) << "the registry should hold at least the three built-in renderers";
  for (const std::string& name : types) {
    const auto renderer = measure::makeRenderer({name, {}});
    VoxelVolume copy = slab();
    VoxelScene scene;
    scene.addVolume(copy, glm::dmat4(1.0), kIso);
    const Trace r = runClosedLoop(scene, renderer->compile(kTool, scene), t, HandModel{}, 3.0);
    ASSERT_EQ(r.forces.size(), 3000u) << name;
    // In contact and pushed back: the force balances the grip.
    EXPECT_GT(r.forces.back(), 0.1) << name;
    // No growing oscillation: the motion in the last half second is under a
    // micrometre, and smaller than in the half second after contact.
    const double late = spread(r, 2500, 3000), early = spread(r, 600, 1100);
    EXPECT_LT(late, 1e-6) << name;
    EXPECT_LE(late, early + 1e-9) << name;
    for (double f : r.forces) ASSERT_TRUE(std::isfinite(f)) << name;
  }
}

TEST(HandDevice, AReleasedHandleCoastsToAStop) {
  VoxelScene empty;
  SurfacePointRenderer renderer;
  HandModel hand;
  hand.releaseTime = 0.5;  // let go while moving at 20 mm/s
  const Trajectory t = line({0, 0.02, 0}, {0.02, 0.02, 0}, 1.0, 1.0);
  const Trace r = runClosedLoop(empty, renderer.compile(kTool, empty), t, hand, 2.0);
  const double speedAfter = glm::length(r.positions[600] - r.positions[599]) * 1000.0;
  const double speedLate = glm::length(r.positions[1999] - r.positions[1998]) * 1000.0;
  EXPECT_GT(speedAfter, 1e-3);
  // Device damping alone: v decays as exp(−b/m·t) = exp(−6.7·1.4 s).
  EXPECT_LT(speedLate, speedAfter * 1e-3);
}
