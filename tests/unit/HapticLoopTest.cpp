// The haptic loop: hand-off structures between threads, the safety layer on
// the device port, renderer swaps, device failure, and the real-time thread.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <thread>

#include <glm/geometric.hpp>

#include "millsim/devices/TrajectoryDevice.h"
#include "millsim/renderers/BarbicRenderer.h"
#include "millsim/renderers/SurfacePointRenderer.h"
#include "millsim/run/FrameLog.h"
#include "millsim/run/HapticLoop.h"
#include "millsim/run/SpscRing.h"
#include "millsim/driver/TripleBuffer.h"
#include "millsim/volume/BlockChannel.h"
#include "millsim/volume/ToothPhantom.h"
#include "millsim/volume/VoxelScene.h"

using namespace millsim;

namespace {

// An algorithm that outputs a fixed force (or whatever `make` says).
class ConstantAlgorithm final : public HapticAlgorithm {
public:
  explicit ConstantAlgorithm(glm::dvec3 force, glm::dvec3 torque = glm::dvec3(0.0)) : force_(force), torque_(torque) {}
  void reset(const Pose&) override {}
  HapticOutput step(HapticScene&, const HapticInput& in) override {
    HapticOutput out;
    out.force = force_;
    out.torque = torque_;
    out.drawnTool = in.device;
    out.burrCuts = false;
    ++steps;
    return out;
  }
  std::string name() const override { return "Constant"; }
  long steps = 0;

private:
  glm::dvec3 force_, torque_;
};

// A device that stands still, records what it was sent, and can be told to
// drop samples or fail.
struct FakeDevice final : DeviceDriver {
  struct Shared {
    std::vector<glm::dvec3> forces, torques;
    long invalidFrom = std::numeric_limits<long>::max(), failAt = std::numeric_limits<long>::max();
    bool stopped = false;
  };
  explicit FakeDevice(Shared& s) : s_(s) { s_.forces.reserve(100000); }
  DeviceReading read(double, double) override {
    ++reads_;
    return {Pose{glm::dvec3(0.0, 0.01, 0.0), glm::dquat(1, 0, 0, 0)}, false, reads_ < s_.invalidFrom};
  }
  void write(const glm::dvec3& f, const glm::dvec3& t) override {
    if (s_.forces.size() < s_.forces.capacity()) {
      s_.forces.push_back(f);
      s_.torques.push_back(t);
    }
  }
  bool failed() const override { return reads_ >= s_.failAt; }
  std::string failure() const override { return "fake device unplugged"; }
  void stop() override { s_.stopped = true; }
  long reads_ = 0;
  Shared& s_;
};

LoopSettings settings(double softStart = 0.0) {
  LoopSettings s;
  s.rate = 1000.0;
  s.limits.forceLimit = 5.0;
  s.limits.torqueLimit = 0.1;
  s.limits.softStartTime = softStart;
  s.timing = false;
  return s;
}

}  // namespace

TEST(SpscRing, KeepsOrderAndCountsDropsWhenFull) {
  SpscRing<int> ring(3);
  for (int i = 0; i < 5; ++i) ring.push(i);
  std::vector<int> got;
  ring.drain([&](int v) { got.push_back(v); });
  EXPECT_EQ(got, (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(ring.dropped(), 2u);
}

TEST(SpscRing, TwoThreadsSeeEveryRecordInOrder) {
  SpscRing<long> ring(64);
  constexpr long kN = 200000;
  std::thread producer([&] {
    for (long i = 0; i < kN; ++i)
      while (!ring.push(i)) std::this_thread::yield();
  });
  long expected = 0;
  bool ordered = true;
  while (expected < kN)
    ring.drain([&](long v) { ordered &= v == expected++; });
  producer.join();
  EXPECT_TRUE(ordered);
}

TEST(TripleBuffer, ReaderGetsTheNewestWholeValue) {
  struct Pair {
    long a = 0, b = 0;
  };
  TripleBuffer<Pair> buffer;
  std::atomic<bool> done{false};
  std::thread writer([&] {
    for (long i = 1; i <= 200000; ++i) {
      buffer.back() = {i, -i};
      buffer.publish();
    }
    done = true;
  });
  long last = 0;
  bool torn = false, backwards = false;
  while (!done || buffer.hasNew()) {
    const Pair& p = buffer.read();
    torn |= p.a != -p.b;
    backwards |= p.a < last;
    last = p.a;
  }
  writer.join();
  EXPECT_FALSE(torn);
  EXPECT_FALSE(backwards);
  EXPECT_EQ(buffer.read().a, 200000);
}

TEST(HapticLoop, ClampsRampsAndZeroesNonFiniteOutput) {
  VoxelScene scene;
  FakeDevice::Shared dev;
  {
    HapticLoop loop(scene, std::make_unique<ConstantAlgorithm>(glm::dvec3(0, 20, 0)),
                    std::make_unique<FakeDevice>(dev), settings(0.1));
    for (int i = 0; i < 300; ++i) loop.stepSimulated();
    loop.finish();
  }
  ASSERT_EQ(dev.forces.size(), 300u);
  // Soft start: 20 N ramps linearly over 0.1 s (and is clamped to 5 N from 25 ms on).
  EXPECT_NEAR(dev.forces[10].y, 20.0 * 0.010 / 0.1, 1e-9);
  EXPECT_NEAR(dev.forces[100].y, 5.0, 1e-9);
  EXPECT_NEAR(dev.forces[299].y, 5.0, 1e-9);
  for (std::size_t i = 1; i < dev.forces.size(); ++i) EXPECT_LE(dev.forces[i].y - dev.forces[i - 1].y, 0.21);
  EXPECT_TRUE(dev.stopped);

  FakeDevice::Shared nan;
  HapticLoop loop(scene,
                  std::make_unique<ConstantAlgorithm>(glm::dvec3(std::numeric_limits<double>::quiet_NaN(), 0, 0),
                                                      glm::dvec3(0, std::numeric_limits<double>::infinity(), 0)),
                  std::make_unique<FakeDevice>(nan), settings());
  for (int i = 0; i < 10; ++i) loop.stepSimulated();
  for (std::size_t i = 0; i < nan.forces.size(); ++i) {
    EXPECT_EQ(nan.forces[i], glm::dvec3(0.0));
    EXPECT_EQ(nan.torques[i], glm::dvec3(0.0));
  }
  EXPECT_EQ(loop.stats().safety.nonFinite, 10u);
}

TEST(HapticLoop, StaleDeviceSamplesTripTheWatchdog) {
  VoxelScene scene;
  FakeDevice::Shared dev;
  dev.invalidFrom = 50;  // the device stops answering after 49 samples
  HapticLoop loop(scene, std::make_unique<ConstantAlgorithm>(glm::dvec3(1, 0, 0)), std::make_unique<FakeDevice>(dev),
                  settings());
  for (int i = 0; i < 100; ++i) loop.stepSimulated();
  ASSERT_EQ(dev.forces.size(), 100u);
  EXPECT_EQ(dev.forces[48], glm::dvec3(1, 0, 0));
  // The 5 ms watchdog: the pose is held for a few frames, then output is zero.
  EXPECT_EQ(dev.forces[52], glm::dvec3(1, 0, 0));
  EXPECT_EQ(dev.forces[60], glm::dvec3(0.0));
  EXPECT_EQ(dev.forces[99], glm::dvec3(0.0));
  EXPECT_GT(loop.stats().safety.watchdogTrips, 40u);
}

TEST(HapticLoop, SwapsRenderersWithACrossFadeAndRetiresTheOldOne) {
  VoxelScene scene;
  FakeDevice::Shared dev;
  HapticLoop loop(scene, std::make_unique<ConstantAlgorithm>(glm::dvec3(1, 0, 0)), std::make_unique<FakeDevice>(dev),
                  settings());
  for (int i = 0; i < 10; ++i) loop.stepSimulated();
  ASSERT_TRUE(loop.replaceRenderer(std::make_unique<ConstantAlgorithm>(glm::dvec3(3, 0, 0))));
  for (int i = 0; i < 200; ++i) loop.stepSimulated();
  EXPECT_NEAR(dev.forces[9].x, 1.0, 1e-12);
  EXPECT_NEAR(dev.forces[60].x, 1.0 + 2.0 * 0.051 / 0.1, 1e-9);  // halfway through the 100 ms fade
  EXPECT_NEAR(dev.forces[209].x, 3.0, 1e-12);
  loop.collectRetired();  // frees the first algorithm here, not on the haptic thread
}

TEST(HapticLoop, LogRowsCarryEveryFrameAndThePeriod) {
  VoxelScene scene;
  FakeDevice::Shared dev;
  HapticLoop loop(scene, std::make_unique<ConstantAlgorithm>(glm::dvec3(0.5, 0, 0)), std::make_unique<FakeDevice>(dev),
                  settings());
  std::ostringstream out;
  FrameLogWriter writer(&out);
  for (int i = 0; i < 3; ++i) {
    loop.stepSimulated();
    writer.drain(loop);
  }
  const std::string log = out.str();
  EXPECT_EQ(log.substr(0, log.find('\n') + 1), frameLogHeader());
  EXPECT_EQ(std::count(log.begin(), log.end(), '\n'), 4);
  EXPECT_NE(log.find("\n0.002,0,0.01,0,1,0,0,0,0.5,0,0,"), std::string::npos) << log;
  const std::string tail = ",1000,Constant," + toolCell(ToolGeometry{}) + "\n";
  EXPECT_EQ(log.substr(log.size() - tail.size()), tail) << "period_us, the renderer's name, then the burr";
}

// The log ends with what the device got at the stop: zero, after the last
// frame, with the renderer's last drawn tool (graphics keep showing it).
TEST(HapticLoop, LogEndsWithTheZeroOutputOfTheStop) {
  VoxelScene scene;
  FakeDevice::Shared dev;
  HapticLoop loop(scene, std::make_unique<ConstantAlgorithm>(glm::dvec3(0.5, 0, 0)), std::make_unique<FakeDevice>(dev),
                  settings());
  std::vector<FrameRecord> rows;
  auto drain = [&] { loop.records().drain([&](const FrameRecord& r) { rows.push_back(r); }); };
  for (int i = 0; i < 3; ++i) loop.stepSimulated();
  drain();
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows.back().force, glm::dvec3(0.5, 0, 0));
  loop.finish();
  loop.finish();  // a second call adds nothing
  drain();
  ASSERT_EQ(rows.size(), 4u);
  const FrameRecord& stop = rows.back();
  EXPECT_TRUE(dev.stopped);
  EXPECT_EQ(stop.frame, 3);
  EXPECT_EQ(stop.t, rows[2].t);
  EXPECT_EQ(stop.force, glm::dvec3(0.0));
  EXPECT_EQ(stop.torque, glm::dvec3(0.0));
  EXPECT_EQ(stop.out.force, glm::dvec3(0.0));
  EXPECT_EQ(stop.out.flags, std::uint32_t(kSafetyStopped));
  EXPECT_EQ(stop.periodUs, 0.0);
  EXPECT_EQ(stop.device.position, rows[2].device.position);
  EXPECT_EQ(stop.out.drawnTool.position, rows[2].out.drawnTool.position);
  EXPECT_STREQ(stop.renderer, "Constant");
  EXPECT_EQ(loop.stats().frames, 3) << "the stop row is not a haptic frame";
}

TEST(HapticLoop, StopWithoutAFrameLogsNothing) {
  VoxelScene scene;
  FakeDevice::Shared dev;
  HapticLoop loop(scene, std::make_unique<ConstantAlgorithm>(glm::dvec3(0.5, 0, 0)), std::make_unique<FakeDevice>(dev),
                  settings());
  loop.finish();
  long n = 0;
  loop.records().drain([&](const FrameRecord&) { ++n; });
  EXPECT_EQ(n, 0);
  EXPECT_TRUE(dev.stopped);
}

// A swap shows in the log: the rows after it name the new renderer.
TEST(HapticLoop, LogNamesTheRendererInChargeAcrossASwap) {
  struct Named final : HapticAlgorithm {
    explicit Named(std::string n) : n_(std::move(n)) {}
    void reset(const Pose&) override {}
    HapticOutput step(HapticScene&, const HapticInput& in) override {
      HapticOutput o;
      o.drawnTool = in.device;
      return o;
    }
    std::string name() const override { return n_; }
    std::string n_;
  };
  VoxelScene scene;
  FakeDevice::Shared dev;
  HapticLoop loop(scene, std::make_unique<Named>("First"), std::make_unique<FakeDevice>(dev), settings());
  std::vector<std::string> names;
  auto drain = [&] { loop.records().drain([&](const FrameRecord& r) { names.push_back(r.renderer); }); };
  loop.stepSimulated();
  std::unique_ptr<HapticAlgorithm> next = std::make_unique<Named>("Second");
  ASSERT_TRUE(loop.replaceRenderer(next));
  EXPECT_EQ(next, nullptr) << "the loop took it";
  std::unique_ptr<HapticAlgorithm> third = std::make_unique<Named>("Third");
  EXPECT_FALSE(loop.replaceRenderer(third)) << "one swap at a time";
  EXPECT_NE(third, nullptr) << "a refused algorithm stays with the caller";
  loop.stepSimulated();
  loop.stepSimulated();
  drain();
  EXPECT_EQ(names, (std::vector<std::string>{"First", "Second", "Second"}));
  // The fade ends after 100 ms; the retired algorithm comes back to this thread.
  for (int i = 0; i < 150; ++i) loop.stepSimulated();
  auto back = loop.takeRetired();
  ASSERT_NE(back, nullptr);
  EXPECT_EQ(back->name(), "First");
}

TEST(HapticLoop, RealTimeThreadRunsStopsOnDeviceFailureAndZeroesOutput) {
  VoxelScene scene;
  FakeDevice::Shared dev;
  dev.failAt = 300;
  LoopSettings s = settings();
  s.timing = true;
  HapticLoop loop(scene, std::make_unique<ConstantAlgorithm>(glm::dvec3(1, 0, 0)), std::make_unique<FakeDevice>(dev),
                  s);
  FrameLogWriter writer(nullptr);
  loop.start(30.0);  // the failure must end it long before
  long lastFrame = -1;
  bool contiguous = true;
  FrameRecord last;
  auto take = [&](const FrameRecord& r) {
    contiguous &= r.frame == lastFrame + 1;
    lastFrame = r.frame;
    last = r;
  };
  while (!loop.finished()) {
    loop.records().drain(take);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  loop.join();
  loop.records().drain(take);
  EXPECT_TRUE(contiguous);
  EXPECT_EQ(lastFrame, 300) << "300 frames, then the stop row";
  EXPECT_EQ(last.out.flags, std::uint32_t(kSafetyStopped));
  EXPECT_EQ(last.force, glm::dvec3(0.0)) << "a failed device is still logged as zeroed";
  EXPECT_EQ(loop.failure(), "fake device unplugged");
  EXPECT_TRUE(dev.stopped);
  const LoopStats st = loop.stats();
  EXPECT_EQ(st.frames, 300);
  // Loose bounds only: a loaded CI machine may be slow, but not 10× slow.
  EXPECT_GT(st.meanRate(), 100.0);
  EXPECT_LT(st.meanRate(), 1100.0);
  EXPECT_EQ(st.recordsDropped, 0u);
}

TEST(HapticLoop, RejectsANonPositiveRate) {
  VoxelScene scene;
  FakeDevice::Shared dev;
  LoopSettings s = settings();
  s.rate = 0.0;
  EXPECT_THROW(HapticLoop(scene, std::make_unique<ConstantAlgorithm>(glm::dvec3(0.0)),
                          std::make_unique<FakeDevice>(dev), s),
               std::invalid_argument);
}

// The three threads of `millsim run` at once: the haptic thread mills the
// phantom and publishes blocks and frames; a graphics thread applies the
// blocks to its replica and reads the newest frame; this (scene) thread drains
// the log. Under ThreadSanitizer (the tsan preset) this is the race check.
TEST(HapticLoop, MillsInRealTimeWhileGraphicsAndSceneThreadsRead) {
  ToothPhantomOptions o = parsePhantomUrl("phantom:tooth?size=64,64,44");
  VoxelVolume volume = makeToothPhantom(o);
  VoxelScene scene;
  scene.addVolume(volume, glm::dmat4(1.0), 700.0);
  BlockChannel channel(256);
  VolumeReplica replica(volume);

  // Down into the top of the tooth with the burr on, then hold.
  const double top = volume.voxelSize().y * volume.dims().y * 0.5;
  const Trajectory t({{0.0, Pose{glm::dvec3(0, top, 0), glm::dquat(1, 0, 0, 0)}, true},
                      {0.3, Pose{glm::dvec3(0, 0, 0), glm::dquat(1, 0, 0, 0)}, true},
                      {0.4, Pose{glm::dvec3(0, 0, 0), glm::dquat(1, 0, 0, 0)}, true}});
  SurfacePointRenderer renderer;
  const ToolGeometry tool{0.6e-3, 0.4e-3, 10e-3};
  LoopSettings s = settings();
  s.tool = tool;
  HapticLoop loop(scene, renderer.compile(tool, scene), makeTrajectoryDriver(t, false), s);
  loop.publishBlocks(0, channel);

  std::atomic<bool> done{false};
  long framesSeen = 0;
  std::thread graphics([&] {
    while (!done.load()) {
      replica.apply(channel);
      framesSeen = std::max(framesSeen, loop.newest().read().frame);
      std::this_thread::sleep_for(std::chrono::milliseconds(3));
    }
  });
  loop.start(t.endTime());
  long rows = 0;
  while (!loop.finished()) {
    rows += long(loop.records().drain([](const FrameRecord&) {}));
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  loop.join();
  rows += long(loop.records().drain([](const FrameRecord&) {}));
  // The haptic thread is done writing: the last blocks are in the channel
  // unless it was full at the end, in which case they are still pending.
  done = true;
  graphics.join();
  replica.apply(channel);

  const LoopStats st = loop.stats();
  EXPECT_GT(st.removedVolume, 0.0);
  EXPECT_EQ(rows, st.frames + 1) << "every frame, then the stop row";
  EXPECT_GT(framesSeen, 0);
  EXPECT_EQ(replica.volume().contentHash(), volume.contentHash()) << "the graphics copy missed a milled block";
}

// A burr swap while running (the B key) compiles Barbic again on the scene
// thread, for the slot that renders and for the waiting one, while the haptic
// thread mills the same scene. The compile must leave the shells alone: the
// haptic thread brings them up to date in step(), and milling writes their
// pending changes. Under ThreadSanitizer (the tsan preset) this is the race
// check; in any build, a shell the run did not build before it started is
// refused while it runs (building it would read voxels being milled).
TEST(HapticLoop, BarbicCompiledOnTheSceneThreadWhileTheHapticThreadMillsLeavesTheShellsAlone) {
  ToothPhantomOptions o = parsePhantomUrl("phantom:tooth?size=64,64,44");
  VoxelVolume volume = makeToothPhantom(o);
  VoxelScene scene;
  scene.addVolume(volume, glm::dmat4(1.0), 700.0);
  const double top = volume.voxelSize().y * volume.dims().y * 0.5;
  const Trajectory t({{0.0, Pose{glm::dvec3(0, top, 0), glm::dquat(1, 0, 0, 0)}, true},
                      {0.3, Pose{glm::dvec3(0, 0, 0), glm::dquat(1, 0, 0, 0)}, true},
                      {0.5, Pose{glm::dvec3(0, 0, 0), glm::dquat(1, 0, 0, 0)}, true}});
  const ToolGeometry tool{0.6e-3, 0.4e-3, 10e-3};
  BarbicRenderer barbic;  // pointShellScale 1: shells at scales 1 and 2
  LoopSettings s = settings();
  s.tool = tool;
  HapticLoop loop(scene, barbic.compile(tool, scene), makeTrajectoryDriver(t, false), s);
  loop.start(t.endTime());
  int compiled = 0;
  std::string refusal;
  while (!loop.finished()) {
    // As RendererPool::followTool and prepare() do for a new burr.
    auto again = barbic.compile(ToolGeometry{0.5e-3, 0.4e-3, 10e-3}, scene);
    compiled += again != nullptr;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  // Still the loop's until join(): a shell it did not have is refused, naming why.
  BarbicRenderer coarser;
  coarser.pointShellScale.set(3);
  try {
    coarser.compile(tool, scene);
  } catch (const std::runtime_error& e) {
    refusal = e.what();
  }
  loop.join();
  EXPECT_GT(compiled, 2);
  EXPECT_GT(loop.stats().removedVolume, 0.0);
  EXPECT_NE(refusal.find("point shell at scale 3"), std::string::npos) << refusal;
  EXPECT_NE(refusal.find("next run"), std::string::npos) << refusal;
  EXPECT_NO_THROW(coarser.compile(tool, scene)) << "once the loop is joined, the scene is the scene thread's again";
}

// The device's live fields reach the haptic thread at the next frame: a new
// force limit clamps, `enabled` false sends nothing, and back again.
TEST(HapticLoop, LiveLimitsAndEnabledApplyFromTheNextFrame) {
  VoxelScene scene;
  FakeDevice::Shared dev;
  HapticLoop loop(scene, std::make_unique<ConstantAlgorithm>(glm::dvec3(2.0, 0, 0)), std::make_unique<FakeDevice>(dev),
                  settings());
  loop.stepSimulated();
  loop.setLive(true, 0.5, 0.1);
  loop.stepSimulated();
  loop.setLive(false, 0.5, 0.1);
  loop.stepSimulated();
  loop.setLive(true, 1e-300 * 0.0, 0.1);  // not positive: the old limit stays
  loop.stepSimulated();
  ASSERT_EQ(dev.forces.size(), 4u);
  EXPECT_NEAR(dev.forces[0].x, 2.0, 1e-12);
  EXPECT_NEAR(dev.forces[1].x, 0.5, 1e-12) << "clamped to the new limit";
  EXPECT_EQ(dev.forces[2].x, 0.0) << "disabled";
  EXPECT_NEAR(dev.forces[3].x, 0.5, 1e-12) << "enabled again; a zero limit is refused";
}

// A stamp the volume's millingBudget could not finish in its frame is
// finished by the frames after it, button released or not, and graphics
// gets every piece.
TEST(HapticLoop, FramesAfterTheCutFinishWhatTheMillingBudgetLeft) {
  class CutsAt final : public HapticAlgorithm {
  public:
    explicit CutsAt(glm::dvec3 c) : c_(c) {}
    void reset(const Pose&) override {}
    HapticOutput step(HapticScene&, const HapticInput& in) override {
      HapticOutput out;
      out.drawnTool = in.device;
      out.burrCentre = c_ + glm::dvec3(0.0, -1e-5 * double(frames_++), 0.0);  // sinking 10 µm a frame
      out.burrCuts = true;
      return out;
    }
    std::string name() const override { return "CutsAt"; }

  private:
    glm::dvec3 c_;
    long frames_ = 0;
  };
  ToothPhantomOptions o = parsePhantomUrl("phantom:tooth?size=64,64,44");
  VoxelVolume volume = makeToothPhantom(o);
  VoxelScene scene;
  scene.addVolume(volume, glm::dmat4(1.0), 700.0);
  scene.volume(0).millingBudget = 100;
  BlockChannel channel(4096);
  VolumeReplica replica(volume);
  const glm::dvec3 c(0.0, volume.voxelSize().y * volume.dims().y * 0.3, 0.0);
  // The button is held for 5 frames, then released.
  const Trajectory t({{0.0, Pose{glm::dvec3(0.0), glm::dquat(1, 0, 0, 0)}, true},
                      {0.0045, Pose{glm::dvec3(0.0), glm::dquat(1, 0, 0, 0)}, true},
                      {0.0046, Pose{glm::dvec3(0.0), glm::dquat(1, 0, 0, 0)}, false},
                      {0.2, Pose{glm::dvec3(0.0), glm::dquat(1, 0, 0, 0)}, false}});
  HapticLoop loop(scene, std::make_unique<CutsAt>(c), makeTrajectoryDriver(t, false), settings());
  loop.publishBlocks(0, channel);
  loop.stepSimulated();
  EXPECT_TRUE(scene.millingPending()) << "a 1 mm burr reads more than 100 densities";
  for (int f = 1; f < 200; ++f) {
    loop.stepSimulated();
    replica.apply(channel);
  }
  EXPECT_FALSE(scene.millingPending());
  // The last stamp queued, frame 4's, was walked to its end: made again at
  // once it changes nothing.
  DirtyBlocks d(volume.dims());
  Miller again(volume, 700.f);
  EXPECT_GT(loop.stats().removedVolume, 0.0);
  EXPECT_EQ(replica.volume().contentHash(), volume.contentHash()) << "graphics missed a piece";
  EXPECT_EQ(again.stamp(c + glm::dvec3(0.0, -4e-5, 0.0), settings().tool.tipRadius, d).voxelsChanged, 0);
}
