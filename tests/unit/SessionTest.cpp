// The Session (millsim/session/Session.h): one run of a scene, whichever
// thread calls its frames. A thread the test creates itself stands for a
// device library's servo scheduler (OpenHaptics' hdScheduleAsynchronous, a
// DHD loop): it calls servoFrame() at 1 kHz while this thread ticks the scene,
// and the log must tell the same story as simulated time does.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <iostream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "millsim/core/NodeRegistry.h"
#include "millsim/devices/HapticsDevice.h"
#include "millsim/run/RunSetup.h"
#include "millsim/session/Session.h"
#include "millsim/x3d/X3DLoader.h"

using namespace millsim;

namespace {

// The live-readout lesson: a TrajectoryDevice (open loop, so the device pose
// is the same function of time however the frames are timed) approaching
// the tooth, pressing from about 1 s and milling from about 1.4 s.
constexpr const char* kScene = MILLSIM_SOURCE_DIR "/x3d/lessons/live-readout.x3d";
constexpr double kSeconds = 2.0;

struct Row {
  double t = 0.0, force = 0.0, removed = 0.0;
  int contacts = 0;
};

std::vector<Row> parseLog(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  {
    std::istringstream h(line);
    for (std::string n; std::getline(h, n, ',');) names.push_back(n);
  }
  auto col = [&](const std::string& n) { return std::size_t(std::find(names.begin(), names.end(), n) - names.begin()); };
  const std::size_t t = col("t"), fx = col("fx"), fy = col("fy"), fz = col("fz"), c = col("contacts"),
                    removed = col("removed_mm3"), flags = col("flags");
  std::vector<Row> rows;
  while (std::getline(in, line)) {
    std::vector<std::string> v;
    std::istringstream s(line);
    for (std::string x; std::getline(s, x, ',');) v.push_back(x);
    if (v.size() < names.size()) continue;
    if (std::stol(v[flags]) & kSafetyStopped) continue;  // the stop row
    Row r;
    r.t = std::stod(v[t]);
    r.force = std::hypot(std::stod(v[fx]), std::stod(v[fy]), std::stod(v[fz]));
    r.contacts = std::stoi(v[c]);
    r.removed = std::stod(v[removed]);
    rows.push_back(r);
  }
  return rows;
}

LoadResult load() {
  LoadResult r = loadSceneFile(kScene, builtinRegistry());
  EXPECT_TRUE(r.ok()) << r.report();
  return r;
}

double firstContact(const std::vector<Row>& rows) {
  for (const Row& r : rows)
    if (r.contacts > 0) return r.t;
  return -1.0;
}

}  // namespace

TEST(Session, AThreadItDidNotCreateDrivesItAsSimulatedTimeDoes) {
  // Simulated time: frame n at n / rate.
  LoadResult simulatedScene = load();
  ASSERT_TRUE(simulatedScene.ok());
  std::ostringstream simulatedLog;
  SessionOptions options;
  options.timing = false;
  options.log = &simulatedLog;
  auto simulated = Session::openDevice(*simulatedScene.scene, options);
  const long frames = long(kSeconds * simulated->rate());
  for (long n = 0; n < frames; ++n) ASSERT_TRUE(simulated->stepSimulated());
  const SessionResult a = simulated->finish();

  // The same scene, its frames called by a thread of this test at 1 kHz of
  // wall time, the scene ticked on this thread as `millsim run` ticks it.
  LoadResult servoScene = load();
  ASSERT_TRUE(servoScene.ok());
  std::ostringstream servoLog;
  options.timing = true;
  options.log = &servoLog;
  auto session = Session::openDevice(*servoScene.scene, options);
  session->startServo(kSeconds);
  std::atomic<long> calls{0};
  std::thread servo([&] {
    auto next = std::chrono::steady_clock::now();
    while (session->servoFrame()) {
      ++calls;
      next += std::chrono::milliseconds(1);
      std::this_thread::sleep_until(next);
    }
  });
  while (!session->finished()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    session->tick();
  }
  servo.join();
  EXPECT_FALSE(session->servoFrame()) << "after the run, a late call does nothing";
  const SessionResult b = session->finish();
  EXPECT_TRUE(b.ok()) << b.failure;
  EXPECT_EQ(b.stats.frames, calls.load()) << "every call that returned true was a frame; the last (past 2 s) was not";

  const std::vector<Row> ra = parseLog(simulatedLog.str()), rb = parseLog(servoLog.str());
  ASSERT_EQ(long(ra.size()), frames);
  ASSERT_EQ(long(rb.size()), b.stats.frames);
  // A loaded 2-core machine may run late, never early: the frames cover the 2 s.
  EXPECT_LE(rb.size(), ra.size() + 1);
  EXPECT_GE(rb.size(), ra.size() / 4) << "a servo thread at 1 kHz made too few frames";
  EXPECT_NEAR(rb.back().t, kSeconds, 0.05);

  // The same events at the same times, within the timing of the frames.
  const double contactA = firstContact(ra), contactB = firstContact(rb);
  ASSERT_GT(contactA, 0.5) << "the lesson's burr touches the tooth within the 2 s";
  EXPECT_NEAR(contactB, contactA, 0.02);
  // The same forces: the simulated run's force at each servo frame's time.
  // Open loop, the pose is the same function of time; milling and the
  // renderer's steps follow the frames' timing, so allow for the force's own
  // change over a few frames.
  std::vector<double> errors;
  for (const Row& r : rb) {
    if (r.t < contactA) continue;  // free motion: both zero
    const long n = std::clamp(long(std::lround(r.t * simulated->rate())), 0L, frames - 1);
    double spread = 0.0;  // how much the simulated force moves within ±3 frames
    for (long k = std::max(0L, n - 3); k <= std::min(frames - 1, n + 3); ++k)
      spread = std::max(spread, std::abs(ra[std::size_t(k)].force - ra[std::size_t(n)].force));
    errors.push_back(std::max(0.0, std::abs(r.force - ra[std::size_t(n)].force) - spread));
  }
  ASSERT_GT(errors.size(), 100u);
  std::sort(errors.begin(), errors.end());
  const double median = errors[errors.size() / 2], p95 = errors[errors.size() * 95 / 100];
  std::cout << "force difference in contact beyond the frames' own change: median " << median << " N, p95 " << p95
            << " N over " << errors.size() << " frames\n";
  EXPECT_LT(median, 0.01) << "median force difference beyond the frames' own change (N)";
  EXPECT_LT(p95, 0.05) << "95th percentile (N)";
  EXPECT_NEAR(b.stats.removedVolume, a.stats.removedVolume, 0.25 * a.stats.removedVolume);
  EXPECT_GT(a.stats.removedVolume, 0.0);
  // The scene thread's ticks set the device node's fields from the frames.
  EXPECT_EQ(findDevice(*servoScene.scene)->hapticsRate.get(), 1000.f);
  EXPECT_GT(findDevice(*servoScene.scene)->contactForce.get(), 0.f);
}

TEST(Session, AServoLoopThatStopsCallingIsReportedAndTheDeviceReleased) {
  LoadResult scene = load();
  ASSERT_TRUE(scene.ok());
  SessionOptions options;
  auto session = Session::openDevice(*scene.scene, options);
  session->startServo(10.0);
  std::thread servo([&] {
    for (int i = 0; i < 50 && session->servoFrame(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  });
  servo.join();  // the "library" stopped calling after 50 ticks, with the run not over
  const SessionResult r = session->finish();
  EXPECT_EQ(r.stats.frames, 50);
  EXPECT_NE(r.failure.find("servo loop stopped calling"), std::string::npos) << r.failure;
}

TEST(Session, StopEndsAServoRunAtTheNextCall) {
  LoadResult scene = load();
  ASSERT_TRUE(scene.ok());
  auto session = Session::openDevice(*scene.scene, SessionOptions{});
  session->startServo(0.0);  // the trajectory's length
  std::atomic<long> calls{0};
  std::thread servo([&] {
    while (session->servoFrame()) {
      if (++calls == 100) session->stop();
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
  });
  servo.join();
  EXPECT_TRUE(session->finished());
  const SessionResult r = session->finish();
  EXPECT_TRUE(r.ok()) << r.failure;
  EXPECT_EQ(r.stats.frames, 100);
}

TEST(Session, ReplayAndAStepwiseDeviceRunWriteTheSameLog) {
  // A replay of the lesson's own trajectory and the opened TrajectoryDevice
  // stepped in simulated time are one run: the same bytes.
  LoadResult a = load(), b = load();
  ASSERT_TRUE(a.ok() && b.ok());
  std::ostringstream logA, logB;
  SessionOptions options;
  options.timing = false;
  options.until = 0.5;
  options.log = &logA;
  const auto trajectory = findDevice(*a.scene)->trajectory();
  ASSERT_TRUE(trajectory);
  const SessionResult ra = Session::replay(*a.scene, *trajectory, options)->runSimulated();
  options.log = &logB;
  auto stepwise = Session::openDevice(*b.scene, options);
  for (long n = 0; n < ra.stats.frames; ++n) ASSERT_TRUE(stepwise->stepSimulated());
  const SessionResult rb = stepwise->finish();
  EXPECT_EQ(ra.stats.frames, 501);
  EXPECT_EQ(logA.str(), logB.str());
  EXPECT_EQ(ra.stats.peakForce, rb.stats.peakForce);
}

TEST(Session, ADeviceRunHasNoEndInSimulatedTimeAndSaysSo) {
  LoadResult scene = load();
  ASSERT_TRUE(scene.ok());
  auto session = Session::openDevice(*scene.scene, SessionOptions{});
  EXPECT_THROW(session->runSimulated(), std::logic_error);
}
