// The Session (millsim/session/Session.h): one run of a scene, whichever
// thread calls its frames. A thread the test creates itself stands for a
// device library's servo scheduler (OpenHaptics' hdScheduleAsynchronous, a
// DHD loop): it calls servoFrame() at 1 kHz while this thread ticks the scene,
// and the log must tell the same story as simulated time does: the same
// contact and milling as frames at n / rate, and, stepped again at its own
// frame times, the same bits.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
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

// A log without one column (frame_us: measured compute time, the one thing that cannot repeat).
std::string withoutColumn(const std::string& log, const std::string& column) {
  std::istringstream in(log);
  std::string line, out;
  long drop = -1;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::istringstream cellsIn(line);
    for (std::string c; std::getline(cellsIn, c, ',');) cells.push_back(c);
    if (drop < 0) drop = long(std::find(cells.begin(), cells.end(), column) - cells.begin());
    for (std::size_t i = 0; i < cells.size(); ++i)
      if (long(i) != drop) out += cells[i] + ",";
    out += "\n";
  }
  return out;
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
  // The same forces: the servo run's own frames, stepped again in simulated
  // time at the times and periods it logged (a review), give every force,
  // torque, pose and milling figure of the log to the last bit. (Against the
  // 1 kHz simulated run above they differ by how each frame's dt differed,
  // which a loaded machine or TSan stretches: that comparison is the contact
  // time and removed volume.)
  LoadResult reviewScene = load();
  ASSERT_TRUE(reviewScene.ok());
  std::ostringstream reviewLog;
  options.timing = false;
  options.log = &reviewLog;
  const RecordedRun recorded = RecordedRun::parse(servoLog.str(), "servo.csv");
  const SessionResult c = Session::review(*reviewScene.scene, recorded, options)->runSimulated();
  EXPECT_EQ(c.stats.frames, b.stats.frames);
  const std::string servoText = withoutColumn(servoLog.str(), "frame_us");
  const std::string reviewText = withoutColumn(reviewLog.str(), "frame_us");
  EXPECT_TRUE(servoText == reviewText) << "the review of the servo run's log differs from it";
  EXPECT_EQ(c.stats.removedVolume, b.stats.removedVolume);
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
