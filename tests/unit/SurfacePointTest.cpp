// Algorithm #2, SurfacePointRenderer: the must-hold contract of issue 14 at
// its defaults (the tool's deepest points, force linear in depth), and the
// paper's variant (deepestPoints FALSE: the sum of eq. 14–21).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "measure/PhysicalReference.h"
#include "measure/PhysicalScenes.h"
#include "measure/Renderers.h"
#include "millsim/core/NodeRegistry.h"
#include "millsim/devices/Trajectory.h"
#include "millsim/renderers/ContactShares.h"
#include "millsim/renderers/DeepestPoint.h"
#include "millsim/renderers/SurfacePointRenderer.h"
#include "millsim/run/HapticLoop.h"
#include "millsim/session/Replay.h"
#include "millsim/volume/VoxelScene.h"
#include "millsim/volume/VoxelVolume.h"
#include "millsim/x3d/X3DLoader.h"
#include "AnalyticScenes.h"

using namespace millsim;
using namespace millsim::test;

namespace {

struct Rig {
  VoxelVolume volume;
  VoxelScene scene;
  std::unique_ptr<HapticAlgorithm> algorithm;
  Rig(VoxelVolume v, const SurfacePointRenderer& renderer, const ToolGeometry& tool = kTool) : volume(std::move(v)) {
    scene.addVolume(volume, glm::dmat4(1.0), kIso);
    algorithm = renderer.compile(tool, scene);
  }
  HapticOutput step(const Pose& p) { return algorithm->step(scene, HapticInput{p, 1e-3}); }
  // Approaches `target` from `from` in 40 steps, then holds it 20 frames.
  HapticOutput press(const Pose& from, const Pose& target) {
    algorithm->reset(from);
    for (int i = 1; i <= 40; ++i) {
      const double u = i / 40.0;
      step(Pose{from.position + (target.position - from.position) * u, glm::slerp(from.orientation, target.orientation, u)});
    }
    HapticOutput out;
    for (int i = 0; i < 20; ++i) out = step(target);
    return out;
  }
};

double k() { return SurfacePointRenderer().springConstant.get(); }

double degreesBetween(const glm::dvec3& a, const glm::dvec3& b) {
  return std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0, 1.0)) * 180.0 / M_PI;
}

}  // namespace

// Must hold (issue 14): a burr whose surface is 0.25 mm inside material is
// pushed out, by the penetration times the spring, along the outward normal.
TEST(SurfacePoint, ABurrWhoseSurfaceIsAQuarterMillimetreInsideASlabIsPushedOut) {
  SurfacePointRenderer r;
  for (double x : {0.0, 0.03e-3, 0.05e-3}) {  // sub-voxel phases
    Rig rig(slab(), r);
    const Pose pressed = vertical({x, kTool.tipRadius - 0.25e-3, 0.013e-3});
    const auto out = rig.press(vertical({x, 1.5e-3, 0}), pressed);
    EXPECT_NEAR(out.force.y, k() * 0.25e-3, 0.05 * k() * 0.25e-3) << x;
    EXPECT_LE(std::hypot(out.force.x, out.force.z), 0.05 * out.force.y) << x;
  }
}

// The force is the spring times the depth from the first touch of the burr's
// surface (5 % of the force at 0.05 mm, the physical suite's floor), past
// the burr centre entering the material too.
TEST(SurfacePoint, TheForceIsLinearInTheDepthFromFirstTouch) {
  SurfacePointRenderer r;
  for (double depth : {0.01e-3, 0.05e-3, 0.1e-3, 0.3e-3, 0.6e-3, 0.8e-3}) {
    Rig rig(slab(), r);
    const auto out = rig.press(vertical({0.02e-3, 1.5e-3, 0}), vertical({0.02e-3, kTool.tipRadius - depth, 0}));
    EXPECT_NEAR(out.force.y, k() * depth, 0.05 * k() * std::max(depth, 0.05e-3)) << depth;
  }
}

// Must hold (issue 14): pressing straight down on a flat face gives a lateral
// force of at most 5 % of the normal force, at every depth, sub-voxel phase and tilt.
TEST(SurfacePoint, PressingStraightDownOnAFlatFaceGivesNoSidewaysForce) {
  SurfacePointRenderer r;
  for (double tilt : {0.0, 0.5, 1.0})
    for (double x : {0.0, 0.037e-3})
      for (double depth : {0.05e-3, 0.1e-3, 0.2e-3, 0.3e-3, 0.6e-3}) {
        Rig rig(slab(), r);
        const glm::dvec3 at(x, kTool.tipRadius - depth, 0.013e-3);
        const auto out = rig.press(tilted(at + glm::dvec3(0, 1.5e-3, 0), tilt), tilted(at, tilt));
        ASSERT_GT(out.force.y, 0.0) << "tilt " << tilt << " x " << x << " depth " << depth;
        EXPECT_LE(std::hypot(out.force.x, out.force.z), 0.05 * out.force.y)
            << "tilt " << tilt << " x " << x << " depth " << depth;
      }
}

// Must hold (issue 14): on a ball the force is within 3° of the normal.
TEST(SurfacePoint, OnABallTheForceIsWithinThreeDegreesOfTheNormal) {
  const double R = 2.0e-3;
  SurfacePointRenderer r;
  Rig rig(analytic(64, [&](const glm::dvec3& p) { return glm::length(p) - R; }), r);
  for (const glm::dvec3 d : {glm::dvec3(0.3, 1.0, 0.2), glm::dvec3(0.4, 1.0, -0.3), glm::dvec3(-0.7, 0.6, 0.1),
                             glm::dvec3(1.0, 0.2, 0.05)})
    for (double depth : {0.05e-3, 0.15e-3, 0.25e-3}) {
      const glm::dvec3 n = glm::normalize(d);
      const auto out = rig.press(vertical(n * (R + kTool.tipRadius + 1.0e-3)), vertical(n * (R + kTool.tipRadius - depth)));
      ASSERT_GT(glm::length(out.force), 0.0) << "depth " << depth;
      EXPECT_LE(degreesBetween(out.force, n), 3.0) << "n " << n.x << "," << n.y << "," << n.z << " depth " << depth;
      // Not the contract's: the voxelised ball's iso-surface lies up to about
      // 0.09 voxel off the true sphere (the one-voxel density ramp), so the
      // depth is good to 8 µm here, not to 5 % of 0.05 mm.
      EXPECT_NEAR(glm::length(out.force), k() * depth, k() * 0.08 * kH) << "depth " << depth;
    }
}

// In a concave corner (a hole's wall and bottom) the burr is pushed out of both.
TEST(SurfacePoint, InACornerTheBurrIsPushedOutOfBothFaces) {
  // Material for y < 0 and for x > 0.6 mm (a wall standing on a floor).
  SurfacePointRenderer r;
  Rig rig(analytic(64, [](const glm::dvec3& p) { return std::min(p.y, 0.6e-3 - p.x); }), r);
  const double d = 0.15e-3;
  const glm::dvec3 at(0.6e-3 - kTool.tipRadius + d, kTool.tipRadius - d, 0.013e-3);
  const auto out = rig.press(vertical(at + glm::dvec3(-1.0e-3, 1.0e-3, 0)), vertical(at));
  EXPECT_NEAR(out.force.x, -k() * d, 0.05 * k() * d);
  EXPECT_NEAR(out.force.y, k() * d, 0.05 * k() * d);
}

// Must hold (issue 14): a shaft leaning on an edge gives torque of the right
// sign with the moment arm within 15 % of the rigid tool's (measure/PhysicalReference).
TEST(SurfacePoint, AShaftLeaningOnAnEdgeIsPushedBackWithTheReferenceMomentArm) {
  using namespace millsim::measure;
  const PhysicalScene ps = physicalScene("shaft-on-edge");
  const double h = 0.1e-3;
  auto scene = voxelise(ps.shape, h);
  const ToolGeometry tool = standardTool();
  SurfacePointRenderer r;
  auto algorithm = r.compile(tool, *scene->scene);
  for (const PhysicalProbe& probe : physicalProbes(ps, tool, h, 2)) {
    const PhysicalPose ref = constrainedPose(ps.material, tool, probe.device, {k()});
    algorithm->reset(Pose{probe.start, probe.device.orientation});
    HapticOutput out;
    for (int i = 1; i <= 40; ++i)
      out = algorithm->step(*scene->scene, {Pose{probe.start + (probe.device.position - probe.start) * (i / 40.0),
                                                  probe.device.orientation}, 1e-3});
    for (int i = 0; i < 20; ++i) out = algorithm->step(*scene->scene, {probe.device, 1e-3});
    const double depth = probe.depth * 1e3;
    ASSERT_GT(glm::length(out.force), 0.0) << depth << " mm";
    EXPECT_GT(glm::dot(out.torque, ref.torque), 0.0) << depth << " mm";
    EXPECT_LE(degreesBetween(out.force, ref.force), 3.0) << depth << " mm";
    const double arm = glm::length(out.torque) / glm::length(out.force);
    EXPECT_NEAR(arm, ref.momentArm, 0.15 * ref.momentArm) << depth << " mm";
  }
}

// A shaft whose axis has gone into a convex edge (the bowl's rim in the
// physical suite's 40° poses) leaves it by the shortest way, at the height
// where that way is longest: what a rigid shaft there is pushed by. Keeping
// the line it entered on (before) measured the rim 0.42 mm deep where a rigid
// shaft is 0.55 mm in, and the force of burr and shaft 10–16° off.
TEST(DeepestOnShaft, AnAxisInsideAnEdgeLeavesByTheShortestWay) {
  // Material where x < 0 and y < 0: the edge is the Z axis. The shaft axis
  // crosses it at right angles, 0.05 mm inside each face at 2 mm up the shaft.
  VoxelVolume volume = analytic(64, [](const glm::dvec3& p) {
    return p.x < 0.0 && p.y < 0.0 ? std::max(p.x, p.y) : std::hypot(std::max(p.x, 0.0), std::max(p.y, 0.0));
  });
  VoxelScene scene;
  scene.addVolume(volume, glm::dmat4(1.0), kIso);
  const double rho = kTool.shaftRadius, inside = 0.05e-3, at = 2e-3;
  const glm::dvec3 axis = glm::normalize(glm::dvec3(-1, 1, 0)), out = glm::normalize(glm::dvec3(1, 1, 0));
  const glm::dvec3 c = glm::dvec3(-inside, -inside, 0.0) - at * axis;
  const glm::dmat3 R = glm::mat3_cast(rotationBetween({0, 1, 0}, axis));
  // The rigid shaft is out once the edge is ρ from the axis along `out`; on
  // the voxelised edge (voxel centres h/2 each side of it) the iso-surface
  // cuts the corner: bilinear density (1 − s)² along the diagonal between the
  // centres is the iso value at s = 1 − 1/√2, (1 − √2/2)·h short of the edge.
  const double exact = rho + std::sqrt(2.0) * inside - (1.0 - std::sqrt(0.5)) * kH;
  // The line into the material is −out; start 30° off it, 0.03 mm down the shaft, as a fresh contact.
  const glm::dvec3 into = glm::transpose(R) * -out;
  double phi = std::atan2(into.z, into.x) + 0.5236, y = at - 0.03e-3, t = rho;
  for (int frame = 0; frame < 10; ++frame) t = deepestOnShaft(scene, c, R, rho, 0.5e-3, kTool.shaftLength, y, phi, t);
  const glm::dvec3 normal = -(R * glm::dvec3(std::cos(phi), 0.0, std::sin(phi)));
  EXPECT_NEAR(rho - t, exact, 0.05 * kH);
  EXPECT_LE(degreesBetween(normal, out), 3.0);
  EXPECT_NEAR(y, at, 2.0 * kH);
}

// The shortest way out takes over from the deepest line without a jolt, and
// pushes as a rigid shaft is pushed: a shaft moved slowly across an edge,
// obliquely, until its axis is 0.1 mm inside one face and 0.05 mm inside
// the other, and back. Holding the line it entered on (before) pushed 13 %
// too little there (0.685 N against 0.785 N): the height where the way out
// is longest moves along the shaft as the shaft moves.
TEST(SurfacePoint, AShaftWhoseAxisEntersAnEdgeIsPushedOutSmoothly) {
  SurfacePointRenderer r;
  Rig rig(analytic(64, [](const glm::dvec3& p) {
            return p.x < 0.0 && p.y < 0.0 ? std::max(p.x, p.y) : std::hypot(std::max(p.x, 0.0), std::max(p.y, 0.0));
          }),
          r);
  const glm::dvec3 axis = glm::normalize(glm::dvec3(-1, 1, 0.1)), out = glm::normalize(glm::dvec3(1, 1, 0));
  const glm::dquat q = rotationBetween({0, 1, 0}, axis);
  // The axis point 2 mm up the shaft at (−δ, −δ/2, 0), δ from −0.1 mm (the
  // shaft into the edge, its axis outside) to +0.1 mm, and back.
  auto pose = [&](double delta) { return Pose{glm::dvec3(-delta, -0.5 * delta, 0.0) - 2e-3 * axis, q}; };
  const double step = 0.5e-6;
  rig.algorithm->reset(pose(-0.3e-3));
  glm::dvec3 last(0.0);
  for (int i = 0; i < 20; ++i) last = rig.step(pose(-0.1e-3)).force;
  double largest = 0.0;
  for (int i = 1; i <= 800; ++i) {
    const double delta = -0.1e-3 + step * (i <= 400 ? i : 800 - i);
    const glm::dvec3 f = rig.step(pose(delta)).force;
    largest = std::max(largest, glm::length(f - last));
    EXPECT_GT(glm::dot(f, out), 0.0) << delta * 1e3 << " mm";
    last = f;
  }
  // k times the motion along `out` (1.5/√2 of a step), and 1 mN for the voxels' ripple.
  EXPECT_LE(largest, k() * 1.5 / std::sqrt(2.0) * step + 1e-3);
  // The rigid shaft at the deepest pose is out once the edge is ρ from its
  // axis: ρ + (0.1 + 0.05)/√2 mm, less the voxelised edge's cut corner.
  const double depth = kTool.shaftRadius + 0.15e-3 / std::sqrt(2.0) - (1.0 - std::sqrt(0.5)) * kH;
  EXPECT_NEAR(glm::length(rig.step(pose(0.1e-3)).force), k() * depth, 0.02 * k() * depth);
}

TEST(SurfacePoint, ForceDoesNotDependOnVertexResolution) {
  for (bool deepest : {true, false}) {
    const double depth = 0.3e-3;
    std::vector<double> forces;
    for (int n : {24, 100, 400}) {
      SurfacePointRenderer r;
      r.deepestPoints.set(deepest);
      r.sphereVertices.set(n);
      Rig rig(slab(), r);
      forces.push_back(rig.press(vertical({0, 1.5e-3, 0}), vertical({0, kTool.tipRadius - depth, 0})).force.y);
    }
    // The paper's 24 points: discretisation error; the deepest points: none to speak of.
    EXPECT_NEAR(forces[0] / forces[2], 1.0, deepest ? 0.01 : 0.25) << deepest;
    EXPECT_NEAR(forces[1] / forces[2], 1.0, deepest ? 0.01 : 0.08) << deepest;
  }
}

// The paper's sum grows as the depth squared (k·d²/4r on a flat face, the
// cap's points each a_i deep), which is why it is no longer the default.
TEST(SurfacePoint, ThePapersSumGrowsAsTheDepthSquared) {
  SurfacePointRenderer r;
  r.deepestPoints.set(false);
  r.sphereVertices.set(400);
  std::vector<double> f;
  for (double depth : {0.1e-3, 0.2e-3, 0.4e-3}) {
    Rig rig(slab(), r);
    f.push_back(rig.press(vertical({0, 1.5e-3, 0}), vertical({0, kTool.tipRadius - depth, 0})).force.y);
    EXPECT_NEAR(f.back(), r.springConstant.get() * depth * depth / (4.0 * kTool.tipRadius),
                0.1 * r.springConstant.get() * depth * depth / (4.0 * kTool.tipRadius)) << depth;
  }
  EXPECT_NEAR(f[2] / f[0], 16.0, 2.0);
}

TEST(SurfacePoint, ThePapersVariantHoldsTheForceWhileTheCentreIsInside) {
  SurfacePointRenderer r;
  r.deepestPoints.set(false);
  Rig rig(slab(), r);
  rig.press(vertical({0, 1.5e-3, 0}), vertical({0, 0.05e-3, 0}));
  const auto before = rig.step(vertical({0, 0.02e-3, 0}));  // centre just outside
  EXPECT_FALSE(before.flags & kFlagHeldForce);
  const auto inside = rig.step(vertical({0, -0.3e-3, 0}));  // centre inside: eq. 17
  EXPECT_EQ(inside.force, before.force);
  EXPECT_TRUE(inside.flags & kFlagHeldForce);
  const auto deeper = rig.step(vertical({0, -0.4e-3, 0}));
  EXPECT_EQ(deeper.force, before.force);
  const auto out = rig.step(vertical({0, 0.1e-3, 0}));  // out again: computed afresh
  EXPECT_NE(out.force, before.force);
}

// By default only the direction is held while the centre is inside: the
// force keeps growing with the depth along it.
TEST(SurfacePoint, WhileTheCentreIsInsideTheDirectionIsHeldAndTheForceStillGrows) {
  SurfacePointRenderer r;
  Rig rig(slab(), r);
  rig.press(vertical({0, 1.5e-3, 0}), vertical({0, 0.05e-3, 0}));
  for (double y : {-0.1e-3, -0.3e-3}) {
    const auto out = rig.step(vertical({0, y, 0}));
    EXPECT_TRUE(out.flags & kFlagHeldForce);
    EXPECT_NEAR(out.force.y, k() * (kTool.tipRadius - y), 0.02 * k() * (kTool.tipRadius - y)) << y;
    EXPECT_LE(std::hypot(out.force.x, out.force.z), 1e-6 * out.force.y);
  }
}

TEST(SurfacePoint, ThePapersSliceHoldsItsReactionWhileItsCentreIsInside) {
  SurfacePointRenderer r;
  r.deepestPoints.set(false);
  r.slices.set(4);
  // A wall for x > 0: lean the shaft in until slice centres cross it.
  Rig rig(analytic(64, [](const glm::dvec3& p) { return -p.x; }), r);
  rig.press(vertical({-0.7e-3, -1.0e-3, 0}), tilted({-0.7e-3, -1.0e-3, 0}, 0.2));
  const auto b = rig.step(tilted({-0.7e-3, -1.0e-3, 0}, 0.6));  // upper slice centres now in the wall
  EXPECT_TRUE(b.flags & kFlagHeldForce);
  EXPECT_TRUE(std::isfinite(b.torque.z));
  EXPECT_GT(b.torque.z, 0.0);
}

TEST(SurfacePoint, DrawsTheToolWhereTheDeviceIs) {
  SurfacePointRenderer r;
  Rig rig(slab(), r);
  const Pose p = tilted({0, 0.1e-3, 0}, 0.3);
  rig.algorithm->reset(p);
  const auto out = rig.step(p);
  EXPECT_EQ(out.drawnTool.position, p.position);
}

// The default lesson (a burr milling its own round pit, then the shaft leant
// on the hole's edge and held) felt smoothly: the force changes little from
// frame to frame. A contact per deepest line — about as deep along many
// lines in the pit — made up to six contacts come and go, 0.065 N a frame on
// average in the hold with the simulated hand shaking 3.5 µm a frame.
namespace {

// A stretch of a replay and the frame-to-frame force change it allows.
struct Segment {
  double from, to, meanLimit, maxLimit;  // s, N
  double sum = 0.0, max = 0.0;
  int count = 0;
};

// Replays the default lesson (SurfacePointRenderer) through `trajectory` and
// checks each segment's mean and largest change of force from one frame to the next.
void expectFeltWithoutShaking(const char* trajectory, std::vector<Segment> segments) {
  LoadResult r = loadSceneFile(MILLSIM_SOURCE_DIR "/x3d/default.x3d", builtinRegistry());
  ASSERT_TRUE(r.ok()) << r.report();
  const Trajectory path = Trajectory::load(trajectory);
  glm::dvec3 last(0.0);
  bool first = true;
  ReplayOptions options;
  options.onFrame = [&](const FrameRecord& f) {
    const double change = glm::length(f.force - last);
    for (Segment& s : segments)
      if (!first && f.t > s.from && f.t < s.to) s.sum += change, s.max = std::max(s.max, change), ++s.count;
    last = f.force, first = false;
  };
  const ReplaySummary summary = replay(*r.scene, path, nullptr, options);
  EXPECT_EQ(summary.rendererName, "SurfacePointRenderer");
  for (const Segment& s : segments) {
    ASSERT_GT(s.count, 0);
    EXPECT_LE(s.sum / s.count, s.meanLimit) << s.from << "-" << s.to << " s: mean force change a frame";
    EXPECT_LE(s.max, s.maxLimit) << s.from << "-" << s.to << " s: largest force change a frame";
  }
}

}  // namespace

// Milling down (the feed moves the cut front every frame), leaning, holding.
TEST(SurfacePoint, TheDefaultLessonIsFeltWithoutShaking) {
  expectFeltWithoutShaking(MILLSIM_SOURCE_DIR "/x3d/trajectories/mill-and-lean.csv",
                           {{2.5, 4.0, 2e-3, 0.03}, {4.2, 6.0, 2e-3, 0.03}, {6.2, 8.0, 1e-4, 1e-3}});
}

// The paper's §8.2 procedure: milling the hole, milling while the shaft leans
// on its rim with the burr on the opposite wall (a wedge, where contacts that
// came and went once gave 1.4 N steps), leaning and holding without the button.
// Measured: largest steps 0.031, 0.054, 0.012, 0.017 N; means under 0.5 mN.
// The hold's one 0.017 N step (t = 25.065 s, 2 % of the 0.88 N held) is the
// burr's tracked deepest line moving 2° to a neighbouring one in the floor of
// the hole this run milled (the contacts' shares, ContactShares.h, mill it a
// little differently from the sum's); chatter would show in the mean.
TEST(SurfacePoint, TheSection82ProcedureIsFeltWithoutShaking) {
  expectFeltWithoutShaking(MILLSIM_SOURCE_DIR "/x3d/trajectories/section-8-2.csv",
                           {{2.5, 13.0, 2e-3, 0.08}, {13.0, 20.0, 2e-3, 0.08}, {20.5, 25.0, 2e-3, 0.08},
                            {25.0, 39.9, 1e-4, 0.02}});
}

// ContactShares.h: cases worked out by hand. δ = Σ λ_i n_i is the push.
namespace {
glm::dvec3 push(const std::vector<glm::dvec3>& n, const std::vector<double>& d, std::vector<double>& shares) {
  shares.assign(n.size(), -1.0);
  contactShares(n.data(), d.data(), int(n.size()), shares.data());
  glm::dvec3 delta(0.0);
  for (std::size_t i = 0; i < n.size(); ++i) delta += shares[i] * n[i];
  return delta;
}
}  // namespace

TEST(ContactShares, OneContactOrContactsAtRightAnglesPushTheirOwnDepths) {
  std::vector<double> s;
  EXPECT_NEAR(glm::length(push({{0, 1, 0}}, {0.2e-3}, s) - glm::dvec3(0, 0.2e-3, 0)), 0.0, 1e-15);
  push({{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {0.1e-3, 0.2e-3, 0.3e-3}, s);
  EXPECT_NEAR(s[0], 0.1e-3, 1e-15);
  EXPECT_NEAR(s[1], 0.2e-3, 1e-15);
  EXPECT_NEAR(s[2], 0.3e-3, 1e-15);
}

TEST(ContactShares, ContactsLessThan90DegreesApartArePushedOutOnce) {
  std::vector<double> s;
  // Burr and shaft on one face: the deeper one's push clears both (the sum pushed 0.3 mm).
  const glm::dvec3 flat = push({{0, 1, 0}, {0, 1, 0}}, {0.2e-3, 0.1e-3}, s);
  EXPECT_NEAR(glm::length(flat - glm::dvec3(0, 0.2e-3, 0)), 0.0, 1e-12);
  // Faces 60° apart, both 0.1 mm deep: the rigid tool's nearest translation
  // meets both planes exactly, δ = d/(1 + cos 60°)·(n1 + n2).
  const glm::dvec3 n1(0, 1, 0), n2(std::sin(M_PI / 3), std::cos(M_PI / 3), 0);
  const glm::dvec3 delta = push({n1, n2}, {0.1e-3, 0.1e-3}, s);
  EXPECT_NEAR(glm::dot(delta, n1), 0.1e-3, 1e-12);
  EXPECT_NEAR(glm::dot(delta, n2), 0.1e-3, 1e-12);
  EXPECT_NEAR(s[0], 0.1e-3 / 1.5, 1e-12);
}

TEST(ContactShares, AWedgePushesEachContactItsOwnDepthAndClearContactsNone) {
  std::vector<double> s;
  // A wedge's faces 150° apart: the rigid tool's shares would be 7.5 times the
  // depths; each is capped at its own.
  const glm::dvec3 n1(1, 0, 0), n2(-std::cos(M_PI / 6), std::sin(M_PI / 6), 0);
  push({n1, n2}, {0.1e-3, 0.05e-3}, s);
  EXPECT_NEAR(s[0], 0.1e-3, 1e-15);
  EXPECT_NEAR(s[1], 0.05e-3, 1e-15);
  push({n1, {0, 1, 0}}, {0.1e-3, -0.05e-3}, s);
  EXPECT_NEAR(s[0], 0.1e-3, 1e-15);
  EXPECT_EQ(s[1], 0.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  push({n1, n2}, {nan, 0.05e-3}, s);
  EXPECT_EQ(s[0], 0.0);
  EXPECT_NEAR(s[1], 0.05e-3, 1e-15);
  push({glm::dvec3(nan), n2}, {0.1e-3, 0.05e-3}, s);
  EXPECT_NEAR(s[1], 0.05e-3, 1e-15) << "a NaN normal spoils no other contact's share";
}
