// Issue 14's must-hold contract on the shipped lessons, for every renderer in
// the registry: the drawn tool turns only with the device, in the default
// lesson's lean the hole's wall pushes the shaft back out, and the §8.2
// procedure is felt without shaking.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "measure/Renderers.h"
#include "millsim/core/NodeRegistry.h"
#include "millsim/run/HapticLoop.h"
#include "millsim/session/Replay.h"
#include "millsim/x3d/X3DLoader.h"

using namespace millsim;
namespace fs = std::filesystem;

namespace {

const fs::path kSource = MILLSIM_SOURCE_DIR;

double degreesBetween(const glm::dquat& a, const glm::dquat& b) {
  const double d = std::min(1.0, std::abs(glm::dot(a, b)));
  return 2.0 * std::acos(d) * 180.0 / 3.14159265358979323846;
}

// The largest turn of the drawn tool in one frame beyond the device's turn in
// that frame (degrees), and when.
struct Turn {
  double degrees = 0.0, t = 0.0;
};

// Replays `scene` through `trajectory` with `renderer` (empty: the scene's own)
// and calls `each` with every frame and the previous one.
template <class F>
void replayFrames(const fs::path& scene, const fs::path& trajectory, const std::string& renderer, F each,
                  double rate = 0.0) {
  LoadResult r = loadSceneFile(scene.string(), builtinRegistry());
  ASSERT_TRUE(r.ok()) << r.report();
  const Trajectory path = Trajectory::load(trajectory.string());
  ReplayOptions options;
  options.renderer = renderer;
  options.rate = rate;
  bool first = true;
  FrameRecord last;
  options.onFrame = [&](const FrameRecord& f) {
    if (!first) each(last, f);
    last = f, first = false;
  };
  replay(*r.scene, path, nullptr, options);
}

Turn largestDrawnTurn(const fs::path& scene, const fs::path& trajectory, const std::string& renderer) {
  Turn worst;
  replayFrames(scene, trajectory, renderer, [&](const FrameRecord& a, const FrameRecord& b) {
    const double turn = degreesBetween(a.out.drawnTool.orientation, b.out.drawnTool.orientation) -
                        degreesBetween(a.device.orientation, b.device.orientation);
    if (turn > worst.degrees) worst = {turn, b.t};
  });
  return worst;
}

class EveryRendererInTheLessons : public ::testing::TestWithParam<std::string> {};

}  // namespace

// The default lesson through each shipped trajectory (the §8.2 procedure
// among them): a drawn tool that turned by itself was #1's, 27° in a frame in
// mill-and-lean (its eq. 12–13 offset), and 10° a frame with the shaft on its
// burr's pit rim (the first surface-felt shaft, when it still turned the drawing).
TEST_P(EveryRendererInTheLessons, TheDrawnToolTurnsOnlyWithTheDevice) {
  for (const char* trajectory : {"mill-and-lean.csv", "press-and-lean.csv", "section-8-2.csv"}) {
    const Turn worst = largestDrawnTurn(kSource / "x3d/default.x3d", kSource / "x3d/trajectories" / trajectory, GetParam());
    EXPECT_LE(worst.degrees, 2.0) << trajectory << ": the drawn tool turned " << worst.degrees
                                  << "° more than the device in one frame, at t = " << worst.t << " s";
  }
}

// Leant 20° towards +x with the burr in the hole, the shaft lies on the hole's
// +x rim: the wall pushes it towards −x at a point above the burr, so the
// force is towards −x and the torque about +z (r × F), righting the tool.
TEST_P(EveryRendererInTheLessons, InTheDefaultLessonsLeanTheWallPushesTheShaftBackOut) {
  double fx = 0.0, tz = 0.0, offAxis = 0.0;
  int frames = 0;
  replayFrames(kSource / "x3d/default.x3d", kSource / "x3d/trajectories/mill-and-lean.csv", GetParam(),
               [&](const FrameRecord&, const FrameRecord& f) {
                 if (f.t < 6.2 || f.t > 8.0) return;  // the hold, leant all the way
                 fx += f.force.x, tz += f.torque.z, ++frames;
                 offAxis = std::max(offAxis, std::hypot(f.torque.x, f.torque.y));
               });
  ASSERT_GT(frames, 0);
  fx /= frames, tz /= frames;
  std::cout << GetParam() << ": mean force x " << fx << " N, torque z " << tz << " N·m, largest off-axis torque "
            << offAxis << " N·m\n";
  EXPECT_LT(fx, 0.0) << "the wall should push the shaft towards −x";
  EXPECT_GT(tz, 0.0) << "the wall should turn the tool back upright (+z)";
}

// The RMS of a force series less its centred 21-sample mean: what shakes
// faster than about 25 Hz at 1 kHz (TheSection82ProcedureIsFeltWithoutShaking).
namespace {
double vibration(const std::vector<glm::dvec3>& force) {
  constexpr int kHalf = 10;
  double sum = 0.0;
  int count = 0;
  for (int i = kHalf; i + kHalf < int(force.size()); ++i) {
    glm::dvec3 mean(0.0);
    for (int j = i - kHalf; j <= i + kHalf; ++j) mean += force[std::size_t(j)];
    mean /= double(2 * kHalf + 1);
    const glm::dvec3 d = force[std::size_t(i)] - mean;
    sum += glm::dot(d, d), ++count;
  }
  return count > 0 ? std::sqrt(sum / count) : 0.0;
}
}  // namespace

// The §8.2 procedure on the default lesson felt without shaking, by every
// renderer: the mean and the largest change of force from one frame to the
// next while milling the hole, milling with the shaft on the rim, leaning, and
// holding still. The closed loop (hand, contacts, milling) is chaotic: a rate
// 1 % off 1 kHz takes it along another path, and #2 shook on the rim in 4 and
// in the lean in 1 of 10 replays at 985–1015 Hz (0.16 and 0.22 N a frame)
// while passing at 1 kHz (docs/algorithms.md, #2), and #1's burr proxy
// stuck and slipped up to 0.21 N in a frame. So it is felt at 990 and 1010 Hz
// as well. Largest changes measured (simulated time, 1000/990/1010 Hz, in the
// segments' order): #1 0.038/0.040/0.040, 0.013/0.017/0.011,
// 0.019/0.015/0.039, 0.002/0.000/0.004 N; #2 0.024/0.024/0.023,
// 0.008/0.010/0.010, 0.027/0.026/0.025, 0.019/0.020/0.017 N; #3
// 0.041/0.040/0.042, 0.001/0.001/0.009, 0.017/0.015/0.014,
// 0.018/0.016/0.016 N (0.176 N while milling before its tool's step was held
// short in the frame it lost all its contacts: docs/algorithms.md, "Tissue
// hardness"; its wedge's lift capped at 2 instead of 6 depths gave 0.041 N
// leaning at 990 Hz, at 3 depths 0.032 N holding at another rate); means
// under 1.5 mN. A step of 0.05 N is 5-10 % of the lean's 0.5-0.9 N, about what a
// hand tells apart: leaning allows that much. #1 with its burr normal taken from the surface's gradient
// (tried, issue 14) rested and slipped a voxel in the lean, 0.155 N, and fails
// it. #1's burr proxy, hopping between the walls of its own hole when the
// shaft pushed the hand off its axis, gave 28 and 36 mN mean, 0.35 and 0.32 N
// largest, leaning and holding.
//
// Nor buzzing: a limit cycle can stay under the step limits (#3 with its
// wedge's lift beyond the deeper depth not scaled by what one contact point
// carries buzzed at 0.19 N and about 40 Hz in the milled pit, 0.098 N a frame
// at most), so each segment's vibration is bounded too: the RMS of the force
// less its centred 21-frame (21 ms) mean, which passes the procedure's own
// motion and keeps what shakes above about 25 Hz. Measured (1000/990/1010 Hz,
// the largest segment): #1 0.0050 N milling, #2 0.0020 N leaning, #3 0.0016
// N milling; #3 with that lift 0.015/0.021/0.020 N milling, which fails it.
TEST_P(EveryRendererInTheLessons, TheSection82ProcedureIsFeltWithoutShaking) {
  constexpr double kVibrationLimit = 0.008;  // N RMS: 1.6x #1's milling, half of the buzzing lift's
  struct Segment {
    const char* what;
    double from, to, meanLimit, maxLimit;  // s, N
    double sum = 0.0, max = 0.0;
    int count = 0;
    std::vector<glm::dvec3> force{};
  };
  for (const double rate : {1000.0, 990.0, 1010.0}) {  // Hz; desiredHapticsRate defaults to 1000
    Segment segments[] = {{"milling", 2.5, 13.0, 3e-3, 0.1},
                          {"milling on the rim", 13.0, 20.0, 2e-3, 0.1},
                          {"leaning", 20.5, 25.0, 2e-3, 0.05},
                          {"holding", 25.0, 39.9, 5e-4, 0.03}};
    replayFrames(
        kSource / "x3d/default.x3d", kSource / "x3d/trajectories/section-8-2.csv", GetParam(),
        [&](const FrameRecord& a, const FrameRecord& b) {
          const double change = glm::length(b.force - a.force);
          for (Segment& s : segments)
            if (b.t > s.from && b.t < s.to)
              s.sum += change, s.max = std::max(s.max, change), ++s.count, s.force.push_back(b.force);
        },
        rate);
    for (const Segment& s : segments) {
      ASSERT_GT(s.count, 0) << s.what;
      EXPECT_LE(s.sum / s.count, s.meanLimit) << s.what << " at " << rate << " Hz: mean force change a frame (N)";
      EXPECT_LE(s.max, s.maxLimit) << s.what << " at " << rate << " Hz: largest force change a frame (N)";
      EXPECT_LE(vibration(s.force), kVibrationLimit) << s.what << " at " << rate << " Hz: vibration (N RMS)";
    }
  }
}

// Each shipped lesson with its own renderer, through the default trajectory.
TEST(ShippedLessons, DrawTheToolTurningOnlyWithTheDevice) {
  for (const auto& entry : fs::directory_iterator(kSource / "x3d/lessons")) {
    if (entry.path().extension() != ".x3d") continue;
    const Turn worst = largestDrawnTurn(entry.path(), kSource / "x3d/trajectories/mill-and-lean.csv", "");
    EXPECT_LE(worst.degrees, 2.0) << entry.path().filename() << ": the drawn tool turned " << worst.degrees
                                  << "° more than the device in one frame, at t = " << worst.t << " s";
  }
}

INSTANTIATE_TEST_SUITE_P(Algorithms, EveryRendererInTheLessons, ::testing::ValuesIn(measure::registeredRenderers()),
                         [](const ::testing::TestParamInfo<std::string>& p) { return p.param; });
