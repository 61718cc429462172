// The renderer contract on analytic volumes, for every renderer type in the
// registry (a plugin renderer is tested too): directions, magnitudes, torque
// signs and degenerate input. Then algorithm-specific tests of #1 (#2's are in
// SurfacePointTest.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <iostream>
#include <map>
#include <limits>
#include <optional>
#include <random>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "measure/Physical.h"
#include "measure/Renderers.h"
#include "millsim/renderers/FreeStart.h"
#include "millsim/renderers/LineProxyRenderer.h"
#include "millsim/renderers/ProxyPoint.h"
#include "millsim/renderers/SurfacePointRenderer.h"
#include "millsim/run/RendererSwitch.h"
#include "millsim/volume/VoxelScene.h"
#include "millsim/volume/VoxelVolume.h"
#include "AnalyticScenes.h"

using namespace millsim;
using namespace millsim::test;

namespace {

struct Rig {
  VoxelVolume volume;
  VoxelScene scene;
  std::unique_ptr<HapticAlgorithm> algorithm;
  Rig(VoxelVolume v, const HapticsRendererNode& renderer) : volume(std::move(v)) {
    scene.addVolume(volume, glm::dmat4(1.0), kIso);
    algorithm = renderer.compile(kTool, scene);
  }
  HapticOutput step(const Pose& p) { return algorithm->step(scene, HapticInput{p, 1e-3}); }
  // Holds the device still at `p` until the output stops changing (at most
  // `limit` frames): a proxy or point renderer is steady at once, a coupled
  // one (#3: the tool is a body pulled by a spring) only after its transient.
  // The contract is about the output at rest; `settled` says whether it came to rest.
  HapticOutput settle(const Pose& p, bool& settled, int limit = 2000) {
    HapticOutput last = step(p);
    for (int i = 0; i < limit; ++i) {
      const HapticOutput out = step(p);
      const bool still = glm::length(out.force - last.force) <= 1e-9 && glm::length(out.torque - last.torque) <= 1e-12;
      last = out;
      if (still) return settled = true, out;
    }
    settled = false;
    return last;
  }
  // Approaches `target` from `from` in small steps (so proxies see the contact begin).
  HapticOutput approach(const Pose& from, const Pose& target, int steps = 40) {
    algorithm->reset(from);
    HapticOutput out;
    for (int i = 1; i <= steps; ++i) {
      const double u = double(i) / steps;
      out = step(Pose{from.position + (target.position - from.position) * u,
                      glm::slerp(from.orientation, target.orientation, u)});
    }
    return out;
  }
};

bool finite(const HapticOutput& o) {
  return std::isfinite(glm::length(o.force)) && std::isfinite(glm::length(o.torque)) &&
         std::isfinite(o.drawnTool.position.x) && std::isfinite(o.drawnTool.orientation.w);
}

}  // namespace

// ---- every registered renderer --------------------------------------------------

// The registry must hold at least the three built-in renderers, or the suite
// below would silently shrink.
TEST(Renderers, TheRegistryListsTheBuiltinRenderers) {
  const std::vector<std::string> names = measure::registeredRenderers();
  for (const char* builtin : {"LineProxyRenderer", "SurfacePointRenderer", "BarbicRenderer"})
    EXPECT_NE(std::find(names.begin(), names.end(), builtin), names.end()) << builtin << " is not registered";
}

class EveryRenderer : public ::testing::TestWithParam<std::string> {
protected:
  std::shared_ptr<HapticsRendererNode> renderer() const { return measure::makeRenderer({GetParam(), {}}); }
  // The part of the tool this renderer feels, measured: the height of the burr
  // centre above a flat surface at first contact (0 for a centre-point proxy,
  // about the burr radius for points on the burr's surface).
  double felt() const {
    static std::map<std::string, double> cache;
    auto it = cache.find(GetParam());
    if (it == cache.end()) it = cache.emplace(GetParam(), measure::contactOffset(*renderer(), kTool, kH)).first;
    return it->second;
  }
  // This renderer against the rigid tool in one physical scene at h = 0.1 mm
  // (measure/Physical.h); empty if the suite gave no row for it.
  std::optional<measure::PhysicalRow> physicalScene(const std::string& scene) const {
    measure::PhysicalConfig config;
    config.scenes = {scene};
    for (const measure::PhysicalRow& r : measure::measurePhysical({GetParam(), {}}, 0.1e-3, config))
      if (r.scene == scene) return r;
    return std::nullopt;
  }
  // A contract bound (a ratio that must stay under `strict`) that a renderer
  // is known to miss, named in kKnownMisses with the reason and a looser
  // bound it must still meet; printed whenever it is used, never silent.
  struct KnownMiss {
    const char* renderer;
    const char* check;
    double allowed;
    const char* why;
  };
  // #2's and #3's earlier misses went with issue 14 (deepestPoints, pointShellScale 1), #1's ball with
  // BurrField::contactNormal.
  static constexpr std::array<KnownMiss, 3> kKnownMisses{{
      {"BarbicRenderer", "ball direction", 5.0,
       "the scale-1 point shell on the voxelised ball: 3.1 and 4.6 degrees at 2 of the 12 poses (0.15 mm in along "
       "(0.3, 1, 0.2), 0.05 mm in along (1, 0.2, 0.05)); RMS under 3 (Barbic.AtItsDefaultsAFlatFacePushesStraightOut"
       "AndABallAlongItsNormal)"},
      {"LineProxyRenderer", "physical hole force", 0.45,
       "38 % RMS: the shaft's share is capped at its own depth (ContactShares.h), so the wedge's 30 degree poses "
       "are pushed by the sum, not lifted; holdWholeTool lifts them (1.1 %) but jams in a milled pit "
       "(docs/algorithms.md, issue 14)"},
      {"SurfacePointRenderer", "physical hole force", 0.5,
       "44 % RMS: its contacts' shares are capped at their own depths (ContactShares.h), so the wedge's 30 degree "
       "poses are pushed by the sum, not lifted as a rigid tool is (docs/algorithms.md, issue 14)"},
  }};
  // The bound `ratio` must meet for this renderer; prints what a known miss excuses.
  double bound(const char* check, double strict, double ratio) const {
    for (const KnownMiss& m : kKnownMisses)
      if (GetParam() == m.renderer && std::string(check) == m.check) {
        if (ratio < strict)
          std::cout << "KNOWN ISSUE NO LONGER REPRODUCES: " << m.renderer << ", " << check << " " << ratio
                    << " meets the contract's " << strict << ", remove the waiver in " << __FILE__ << "\n";
        else
          std::cout << "KNOWN ISSUE (" << m.renderer << ", " << check << "): " << ratio << " > the contract's "
                    << strict << ", allowed up to " << m.allowed << ": " << m.why << "\n";
        return m.allowed;
      }
    return strict;
  }
};

TEST_P(EveryRenderer, FreeSpaceGivesNothing) {
  Rig rig(slab(), *renderer());
  rig.approach(vertical({0, 2e-3, 0}), vertical({0.5e-3, 1.0e-3, 0}));
  bool settled = false;
  auto out = rig.settle(vertical({0.5e-3, 1.0e-3, 0}), settled);
  ASSERT_TRUE(settled) << "the output kept changing with the device held still in free space";
  EXPECT_EQ(out.force, glm::dvec3(0.0));
  EXPECT_EQ(out.torque, glm::dvec3(0.0));
  EXPECT_EQ(out.contacts, 0);
}

TEST_P(EveryRenderer, ForcePointsOutOfASlabAndGrowsWithDepth) {
  double previous = 0.0;
  for (double depth : {0.1e-3, 0.2e-3, 0.3e-3}) {
    Rig rig(slab(), *renderer());
    // #1 feels the burr centre; #2 the sphere's surface: press the part each one feels.
    const double y = felt() - depth;
    rig.approach(vertical({0, 1.5e-3, 0}), vertical({0, y, 0}));
    bool settled = false;
    auto out = rig.settle(vertical({0, y, 0}), settled);
    ASSERT_TRUE(settled) << depth << ": the output did not come to rest";
    EXPECT_GT(out.force.y, 0.0) << depth;
    const double sideways = (std::abs(out.force.x) + std::abs(out.force.z)) / out.force.y;
    EXPECT_LT(sideways, bound("slab sideways force", 0.05, sideways)) << depth << ": sideways / normal force";
    EXPECT_GT(glm::length(out.force), previous) << depth;
    previous = glm::length(out.force);
    // A vertical tool pressed straight down: no torque to speak of.
    EXPECT_LT(glm::length(out.torque), 1e-3 * glm::length(out.force) * kTool.shaftLength) << depth;
  }
}

TEST_P(EveryRenderer, ForcePointsOutOfABallAlongTheNormal) {
  const double R = 2.0e-3;
  const glm::dvec3 dir = glm::normalize(glm::dvec3(0.4, 1.0, -0.3));
  // Press the part the renderer feels (measured) 0.2 mm in.
  const double felt = this->felt();
  Rig rig(analytic(64, [&](const glm::dvec3& p) { return glm::length(p) - R; }), *renderer());
  rig.approach(vertical(dir * (R + felt + 0.8e-3)), vertical(dir * (R + felt - 0.2e-3)));
  bool settled = false;
  auto out = rig.settle(vertical(dir * (R + felt - 0.2e-3)), settled);
  ASSERT_TRUE(settled) << "the output did not come to rest";
  ASSERT_GT(glm::length(out.force), 0.0);
  EXPECT_GT(glm::dot(glm::normalize(out.force), dir), 0.95);
}

TEST_P(EveryRenderer, ForcePointsOutOfTheWallOfADrilledHole) {
  // A slab (y < 0) with a vertical hole of radius 1 mm drilled through it.
  const double hole = 1.0e-3;
  Rig rig(analytic(64, [&](const glm::dvec3& p) { return std::max(p.y, hole - std::hypot(p.x, p.z)); }),
          *renderer());
  const double felt = this->felt();
  // Down the middle of the hole, then sideways into its +X wall.
  const Pose above = vertical({0, 1.0e-3, 0}), inHole = vertical({0, -1.0e-3, 0});
  rig.approach(above, inHole);
  HapticOutput out;
  for (int i = 1; i <= 40; ++i) out = rig.step(vertical({(hole - felt + 0.15e-3) * i / 40.0, -1.0e-3, 0}));
  bool settled = false;
  out = rig.settle(vertical({hole - felt + 0.15e-3, -1.0e-3, 0}), settled);
  ASSERT_TRUE(settled) << "the output did not come to rest";
  ASSERT_GT(glm::length(out.force), 0.0);
  EXPECT_LT(out.force.x, 0.0);
  EXPECT_GT(-out.force.x, 3.0 * (std::abs(out.force.y) + std::abs(out.force.z)));
}

TEST_P(EveryRenderer, ShaftAgainstAWallGivesTorqueLikeRCrossF) {
  // Material for x > 0.4 mm; the burr is free, the shaft leans into the wall.
  Rig rig(analytic(64, [](const glm::dvec3& p) { return 0.4e-3 - p.x; }), *renderer());
  const Pose start = vertical({-0.6e-3, -1.0e-3, 0});
  const Pose lean = tilted({-0.6e-3, -1.0e-3, 0}, 0.45);
  rig.approach(start, lean, 60);
  bool settled = false;
  auto out = rig.settle(lean, settled);
  ASSERT_TRUE(settled) << "the output did not come to rest";
  ASSERT_GT(glm::length(out.torque), 0.0);
  // The wall pushes the shaft back (−X) at a point above the tip (+Y): r × F is +Z.
  EXPECT_GT(out.torque.z, 0.0);
  const double offAxis = (std::abs(out.torque.x) + std::abs(out.torque.y)) / std::abs(out.torque.z);
  EXPECT_LT(offAxis, bound("wall off-axis torque", 0.1, offAxis)) << "off-axis / z torque";
}

// Issue 14's must-hold, against the rigid tool (measure/PhysicalReference): a
// shaft leaning on an edge is pushed back, with the torque of the right sign
// and the moment arm within 15 % of the reference's, at h = 0.1 mm. #1's
// paper shaft gave torque and no force at all (no moment arm) on these poses.
TEST_P(EveryRenderer, AShaftLeaningOnAnEdgeIsPushedBackWithTheReferenceMomentArm) {
  const auto row = physicalScene("shaft-on-edge");
  ASSERT_TRUE(row);
  EXPECT_EQ(row->missed, 0.0) << "poses pressed on the edge with no force";
  // |T − T_ref| relative to |F_ref|·arm_ref: a torque of the wrong sign is about 2.
  EXPECT_LT(row->torqueRms, 0.5);
  EXPECT_LT(row->armRelRms, 0.15) << "moment arm RMS relative to the reference's";
}

// Issue 14's must-holds for the burr, over the registry (the per-renderer
// tests in LineProxy, SurfacePoint and Barbic say more about each): pressed
// straight down on a flat face, the lateral force is at most 5 % of the
// normal force at every depth of the burr's surface (0.05–0.6 mm), sub-voxel
// phase and shaft tilt; a burr whose surface is 0.25 mm inside is pushed out.
TEST_P(EveryRenderer, PressingStraightDownOnAFlatFaceGivesAtMostFivePercentSidewaysForce) {
  for (double tilt : {0.0, 0.5})
    for (double x : {0.0, 0.037e-3})
      for (double depth : {0.05e-3, 0.1e-3, 0.2e-3, 0.25e-3, 0.3e-3, 0.6e-3}) {
        Rig rig(slab(), *renderer());
        const glm::dvec3 at(x, kTool.tipRadius - depth, 0.013e-3);
        rig.approach(tilted(at + glm::dvec3(0, 1.5e-3, 0), tilt), tilted(at, tilt));
        bool settled = false;
        const auto out = rig.settle(tilted(at, tilt), settled);
        const std::string where = "tilt " + std::to_string(tilt) + " x " + std::to_string(x) + " depth " +
                                  std::to_string(depth);
        ASSERT_TRUE(settled) << where;
        ASSERT_GT(out.force.y, 0.0) << where << ": not pushed out";
        EXPECT_LE(std::hypot(out.force.x, out.force.z), 0.05 * out.force.y) << where;
      }
}

// A renderer that starts with the tool inside material (a run that starts
// there, or one swapped in while the hand presses: RendererSwitch resets it at
// the device pose) renders what it holds when the hand has pushed in to that
// pose, and never pulls the tool in. #3 pulled it in (its contacts' normals
// point away from a burr centre past the surface: -0.63 N at 0.2 mm), #1
// felt nothing, and #2 with its centre inside held nothing (eq. 17 had no
// entry to hold), before FreeStart.h and #2's axis seed.
TEST_P(EveryRenderer, ATakeOverInsideMaterialRendersWhatPushingInDoes) {
  for (const double centre : {kTool.tipRadius - 0.25e-3, -0.2e-3}) {  // the burr's surface 0.25 mm in; its centre 0.2 mm in
    const Pose at = vertical({0.0, centre, 0.013e-3});
    bool settled = false;
    Rig pushed(slab(), *renderer());
    pushed.approach(vertical(at.position + glm::dvec3(0, 1.5e-3, 0)), at);
    const HapticOutput reference = pushed.settle(at, settled);
    ASSERT_TRUE(settled);
    Rig started(slab(), *renderer());
    started.algorithm->reset(at);
    const HapticOutput out = started.settle(at, settled);
    ASSERT_TRUE(settled);
    const std::string where = "burr centre at y = " + std::to_string(centre * 1e3) + " mm";
    EXPECT_GE(out.force.y, 0.0) << where << ": pulls the tool into the material";
    ASSERT_GT(reference.force.y, 0.0) << where;
    const double ratio = glm::length(out.force - reference.force) / reference.force.y;
    const char* check = centre < 0.0 ? "take-over with the burr centre inside" : "take-over with the burr surface inside";
    EXPECT_LE(ratio, bound(check, 0.05, ratio)) << where << ": " << out.force.y << " N started there, "
                                                 << reference.force.y << " N pushed in";
  }
}

// FreeStart.h's search: the first free distance to within the tolerance,
// through a run of material, none when free already, and a clear "none"
// where the material goes on past the reach or the lengths are not positive.
TEST(FreeStart, FindsTheFirstFreeDistanceAlongTheWay) {
  auto slab = [](double from, double to) { return [=](double s) { return s >= from && s < to; }; };
  EXPECT_EQ(firstFreeAlong(slab(0.3, 0.5), 0.1, 10.0, 1e-3), 0.0) << "free where it starts";
  const double s = firstFreeAlong(slab(-1.0, 0.737), 0.1, 10.0, 1e-3);
  EXPECT_GE(s, 0.737);
  EXPECT_LE(s, 0.737 + 1e-3);
  EXPECT_LT(firstFreeAlong(slab(-1.0, 20.0), 0.1, 10.0, 1e-3), 0.0) << "inside all the way";
  EXPECT_LT(firstFreeAlong(slab(-1.0, 0.5), 0.0, 10.0, 1e-3), 0.0) << "a zero step (no voxels)";
  EXPECT_LT(firstFreeAlong(slab(-1.0, 0.5), 0.1, 10.0, 0.0), 0.0) << "a zero tolerance";
  int tests = 0;
  firstFreeAlong([&](double d) { return ++tests, d < 0.55e-3; }, 0.1e-3, 15.6e-3, 0.005e-3);
  EXPECT_LE(tests, 12) << "a 0.55 mm way out to 0.05 voxel";
}

// Issue 14's must-hold on a convex surface, over the registry: pressed along
// the normal of a 2 mm ball, 0.05–0.25 mm in, the force at rest is within 3°
// of the normal.
TEST_P(EveryRenderer, OnABallTheForceIsWithinThreeDegreesOfTheNormal) {
  const double R = 2.0e-3;
  double worst = 0.0;
  std::string worstPose;
  for (const glm::dvec3 d : {glm::dvec3(0.3, 1.0, 0.2), glm::dvec3(0.4, 1.0, -0.3), glm::dvec3(-0.7, 0.6, 0.1),
                             glm::dvec3(1.0, 0.2, 0.05)})
    for (double depth : {0.05e-3, 0.15e-3, 0.25e-3}) {
      Rig rig(analytic(64, [&](const glm::dvec3& p) { return glm::length(p) - R; }), *renderer());
      const glm::dvec3 n = glm::normalize(d);
      const Pose pressed = vertical(n * (R + kTool.tipRadius - depth));
      rig.approach(vertical(n * (R + kTool.tipRadius + 1.0e-3)), pressed);
      bool settled = false;
      const auto out = rig.settle(pressed, settled);
      ASSERT_TRUE(settled);
      ASSERT_GT(glm::length(out.force), 0.0) << "depth " << depth;
      const double degrees = std::acos(std::clamp(glm::dot(glm::normalize(out.force), n), -1.0, 1.0)) * 180.0 / M_PI;
      if (degrees > worst)
        worst = degrees, worstPose = "along (" + std::to_string(d.x) + ", " + std::to_string(d.y) + ", " +
                                     std::to_string(d.z) + "), " + std::to_string(depth * 1e3) + " mm in";
    }
  EXPECT_LE(worst, bound("ball direction", 3.0, worst)) << "worst " << worstPose;
}

// Issue 14's concave surface, against the rigid tool: the burr pressed into
// a 2 mm bowl's wall, the tool tilted 0, 30 and 60° (at 60° the shaft also
// rests on the rim, less than 90° from the wall's normal, so one push clears
// both). Force within 10 % RMS of the reference's at h = 0.1 mm. #2 summed
// the burr's and the shaft's pushes: 43.8 %, up to twice the force.
TEST_P(EveryRenderer, ABurrInABowlWithItsShaftOnTheRimIsPushedOutOnce) {
  const auto row = physicalScene("bowl");
  ASSERT_TRUE(row);
  EXPECT_EQ(row->missed, 0.0) << "poses pressed into the bowl with no force";
  EXPECT_LT(row->forceRms, 0.10) << "force RMS relative to the reference's";
}

// Issue 14's direction goal: against the rigid tool, the force within 3° RMS
// of the reference's on a flat face, a convex and a concave surface (the
// physical suite's half-space, ball and bowl at h = 0.1 mm). #3's bowl was
// 3.5° before rigidContact took its burr's and shaft's contacts apart.
TEST_P(EveryRenderer, PushesWithinThreeDegreesOnFlatConvexAndConcaveSurfaces) {
  for (const char* scene : {"half-space", "ball", "bowl"}) {
    const auto row = physicalScene(scene);
    ASSERT_TRUE(row) << scene;
    EXPECT_LE(row->directionRms, 3.0) << scene << ": direction RMS (degrees) against the rigid tool's";
  }
}

// A tool tilted 15° and 30° in a drilled hole, the burr pressed into the
// wall and the bottom: at 30° the shaft meets the far rim too, a wedge, and a
// rigid tool held at the device's orientation is lifted by several times the
// depths (the physical reference). Issue 14's force goal (5 % RMS) on it.
// #3 moves the rigid tool out in its coupling's metric, lifting and turning
// it (rigidContact): 1.2 %; translated out and capped at the depth, 16.6 %. #1's and #2's defaults miss it (named
// waivers): each caps its contacts' shares at their own depths, as the
// whole tool's lift jammed and jumped in the default lesson's milled pit
// (docs/algorithms.md). #1's holdWholeTool meets it (LineProxy test below).
TEST_P(EveryRenderer, AToolWedgedInADrilledHoleIsPushedOutAsARigidToolIs) {
  const auto row = physicalScene("hole");
  ASSERT_TRUE(row);
  EXPECT_EQ(row->missed, 0.0) << "poses pressed into the hole with no force";
  EXPECT_LE(row->forceRms, bound("physical hole force", 0.05, row->forceRms)) << "force RMS relative to the reference's";
}

// A burr pushed past a convex edge straight down its bisector (its centre
// 0.1 mm inside the quarter-space) rests on a saddle: a rigid burr slides
// onto a face. #1's proxy and #2's held line stayed on the bisector, 45° off
// there (edge 22.5° and 22.2° RMS); now 3.9° and 6.2° (#2's rest: its 60°
// poses), #3 4.6° (docs/accuracy.md).
TEST_P(EveryRenderer, ABurrPushedPastAConvexEdgeSlidesOffItsBisector) {
  const auto row = physicalScene("edge");
  ASSERT_TRUE(row);
  EXPECT_LT(row->directionRms, 8.0) << "edge: degrees RMS against the rigid burr";
}

// A scene author's mesh (issue 45): the ball as a 20 480-triangle mesh,
// voxelised as a mesh url is, feels as the ball voxelised from its exact
// distance (the same lattice): force and direction errors within 0.5
// percentage points and 0.3 degrees (measured: at most +0.23 points, #3).
TEST_P(EveryRenderer, AMeshBallFeelsAsTheExactBallDoes) {
  const auto exact = physicalScene("ball"), mesh = physicalScene("mesh-ball");
  ASSERT_TRUE(exact && mesh);
  std::printf("%s: ball force %.2f %%, direction %.2f deg; mesh-ball %.2f %%, %.2f deg\n", GetParam().c_str(),
              100 * exact->forceRms, exact->directionRms, 100 * mesh->forceRms, mesh->directionRms);
  EXPECT_EQ(mesh->poses, exact->poses);
  EXPECT_LE(mesh->forceRms, exact->forceRms + 0.005);
  EXPECT_LE(mesh->directionRms, exact->directionRms + 0.3);
  EXPECT_EQ(mesh->missed, 0.0);
}

// The physical suite compares each renderer's output at rest: held ten times
// as long, the figures do not move. A fixed 60-frame hold failed it: #3's
// coupled tool was still sliding off the edge's saddle (edge direction 4.7°
// after 60 frames, 0.47° at rest at h = 0.1 mm). The edge (saddles) and the
// hole (wedges) are where a renderer takes longest to rest.
TEST_P(EveryRenderer, ThePhysicalSuiteComparesTheOutputAtRest) {
  measure::PhysicalConfig held;
  held.scenes = {"edge", "hole"};
  measure::PhysicalConfig longer = held;
  longer.minSettleFrames = longer.settleFrames = 10 * held.settleFrames;
  const auto a = measure::measurePhysical({GetParam(), {}}, 0.1e-3, held);
  const auto b = measure::measurePhysical({GetParam(), {}}, 0.1e-3, longer);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_NEAR(a[i].forceRms, b[i].forceRms, 1e-4) << a[i].scene << ": force RMS (relative)";
    EXPECT_NEAR(a[i].directionRms, b[i].directionRms, 0.05) << a[i].scene << ": direction RMS (degrees)";
    EXPECT_NEAR(a[i].torqueRms, b[i].torqueRms, 1e-4) << a[i].scene << ": torque RMS";
  }
}

// Issue 14's direction goal on its three surfaces, against the rigid tool at
// h = 0.1 mm: flat (half-space), convex (ball) and concave (bowl), each
// pressed straight and obliquely 0.05-0.6 mm in, within 3° RMS of the
// reference's force. #1's and #3's misses are named waivers.
TEST_P(EveryRenderer, OnFlatConvexAndConcaveSurfacesTheForceIsWithinThreeDegreesRms) {
  for (const char* scene : {"half-space", "ball", "bowl"}) {
    const auto row = physicalScene(scene);
    ASSERT_TRUE(row) << scene;
    const std::string check = "physical " + std::string(scene) + " direction";
    EXPECT_LE(row->directionRms, bound(check.c_str(), 3.0, row->directionRms)) << scene << ", degrees RMS";
  }
}

// Issue 14's convergence must-hold: halving the voxel size reduces each
// renderer's force error against the rigid tool (all physical scenes, h =
// 0.2 and 0.1 mm). Contacts summed instead of sharing one push
// (ContactShares.h) failed it: #2 20.2 → 20.8 %, #1 20.4 → 21.6 % (the
// bowl's model error does not shrink with the voxels).
TEST_P(EveryRenderer, HalvingTheVoxelSizeReducesThePhysicalForceError) {
  auto all = [&](double h) {
    const auto rows = measure::measurePhysical({GetParam(), {}}, h, {});
    return rows.back().forceRms;  // the "all" row
  };
  const double coarse = all(0.2e-3), fine = all(0.1e-3);
  std::cout << GetParam() << ": force RMS " << coarse << " at h = 0.2 mm, " << fine << " at 0.1 mm\n";
  EXPECT_LT(fine, coarse);
}

TEST_P(EveryRenderer, DegeneratePosesNeverGiveNonFiniteOutput) {
  Rig rig(slab(), *renderer());
  rig.algorithm->reset(vertical({0, 1e-3, 0}));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Pose poses[] = {
      vertical({0, 0, 0}),                                   // exactly on the iso-surface
      vertical({0, -2e-3, 0}),                               // deep in homogeneous material (zero gradient)
      Pose{{0, -2e-3, 0}, glm::angleAxis(M_PI, glm::dvec3(1, 0, 0))},  // a 180° flip
      vertical({0, 2e-3, 0}),
      vertical({0.3, -0.2, 0.1}),                            // a jump of thousands of voxels
      vertical({nan, 0, 0}),                                 // NaN
      Pose{{0, 0, 0}, glm::dquat(nan, 0, 0, 0)},
      vertical({0, -1e-3, 0}),
      tilted({1e-3, -1e-3, 0}, 3.0),
  };
  for (const Pose& p : poses) {
    const auto out = rig.step(p);
    EXPECT_TRUE(finite(out));
  }
}

// RendererTraits::compilesWithoutScene is exact: a renderer that claims it (its
// fields are then live, RendererPool) reads nothing of the scene when it
// compiles, and one that does not claim it does read the scene (else it
// should claim it). Compiled against a scene that counts every read.
TEST_P(EveryRenderer, CompilesWithoutTheSceneExactlyWhenItSaysSo) {
  struct Untouchable final : HapticScene {
    mutable int reads = 0;
    std::size_t volumeCount() const override { return ++reads, 1; }
    const Placement& placement(std::size_t) const override {
      ++reads;
      static const Placement p{};
      return p;
    }
    double field(const glm::dvec3&) const override { return ++reads, 1.0; }
    glm::dvec3 gradient(const glm::dvec3&) const override { return ++reads, glm::dvec3(0, 1, 0); }
    double voxelSize() const override { return ++reads, 1e-4; }
    const PointShellQuery& pointShell(std::size_t, int) override {
      ++reads;
      throw std::logic_error("pointShell read");
    }
  };
  const auto node = renderer();
  Untouchable scene;
  try {
    node->compile(kTool, scene);
  } catch (const std::logic_error&) {
    // pointShell() refused: counted as a read.
  }
  if (node->traits().compilesWithoutScene)
    EXPECT_EQ(scene.reads, 0) << GetParam() << " says compilesWithoutScene but read the scene";
  else
    EXPECT_GT(scene.reads, 0) << GetParam() << " reads nothing of the scene: it should say compilesWithoutScene";
}

INSTANTIATE_TEST_SUITE_P(Algorithms, EveryRenderer, ::testing::ValuesIn(measure::registeredRenderers()),
                         [](const ::testing::TestParamInfo<std::string>& p) { return p.param; });

// ---- Algorithm #1 --------------------------------------------------------------

TEST(LineProxy, TipForceIsSpringConstantTimesProxyDistance) {
  LineProxyRenderer r;
  Rig rig(slab(), r);
  auto out = rig.approach(vertical({0, 1e-3, 0}), vertical({0.2e-3, -0.25e-3, 0}));
  ASSERT_TRUE(out.hasProxy);
  const glm::dvec3 device(0.2e-3, -0.25e-3, 0);
  EXPECT_NEAR(glm::length(out.force), r.springConstant.get() * glm::length(out.proxy - device), 1e-9);
  // The proxy is the burr's centre, held with the burr's surface on the surface.
  EXPECT_NEAR(out.proxy.y, kTool.tipRadius, 0.2 * kH);
  EXPECT_NEAR(out.force.y, r.springConstant.get() * (kTool.tipRadius + 0.25e-3), 0.2 * kH * r.springConstant.get());
  EXPECT_NEAR(out.drawnTool.position.y, kTool.tipRadius, 0.3 * kH);
}

// The paper's variant (feelBurrSurface false): the centre vertex's proxy sits
// on the surface and the burr is drawn a radius out along the normal (§4.5).
TEST(LineProxy, ThePapersCentreVertexIsHeldOnTheSurfaceAndDrawnARadiusOut) {
  LineProxyRenderer r;
  r.feelBurrSurface.set(false);
  Rig rig(slab(), r);
  auto out = rig.approach(vertical({0, 1e-3, 0}), vertical({0.2e-3, -0.25e-3, 0}));
  ASSERT_TRUE(out.hasProxy);
  EXPECT_NEAR(out.proxy.y, 0.0, 0.2 * kH);
  EXPECT_NEAR(out.force.y, r.springConstant.get() * 0.25e-3, 0.2 * kH * r.springConstant.get());
  EXPECT_NEAR(out.drawnTool.position.y, kTool.tipRadius, 0.3 * kH);
  // The burr's surface 0.25 mm in, its centre still out: nothing is felt.
  Rig shallow(slab(), r);
  out = shallow.approach(vertical({0, 1.5e-3, 0}), vertical({0, kTool.tipRadius - 0.25e-3, 0}));
  EXPECT_EQ(out.force, glm::dvec3(0.0));
}

// Must hold (issue 14): a burr whose surface is 0.25 mm inside material is
// pushed out, by the penetration times the spring, along the outward normal.
TEST(LineProxy, ABurrWhoseSurfaceIsAQuarterMillimetreInsideASlabIsPushedOut) {
  LineProxyRenderer r;
  for (double x : {0.0, 0.03e-3, 0.05e-3}) {  // sub-voxel phases
    Rig rig(slab(), r);
    const Pose pressed = vertical({x, kTool.tipRadius - 0.25e-3, 0});
    rig.approach(vertical({x, 1.5e-3, 0}), pressed);
    bool settled = false;
    const auto out = rig.settle(pressed, settled);
    ASSERT_TRUE(settled) << x;
    EXPECT_GT(out.force.y, 0.0) << x;
    EXPECT_NEAR(out.force.y, r.springConstant.get() * 0.25e-3, 0.05 * r.springConstant.get() * 0.25e-3) << x;
    EXPECT_LE(std::hypot(out.force.x, out.force.z), 0.05 * out.force.y) << x;
    // Drawn where the burr rests on the surface.
    EXPECT_NEAR(out.drawnTool.position.y, kTool.tipRadius, 0.2 * kH) << x;
  }
}

// Must hold (issue 14): pressing straight down on a flat face gives a lateral
// force of at most 5 % of the normal force, at every depth of the burr's
// surface, sub-voxel phase and shaft tilt.
TEST(LineProxy, PressingStraightDownOnAFlatFaceGivesNoSidewaysForce) {
  LineProxyRenderer r;
  for (double tilt : {0.0, 0.5})
    for (double x : {0.0, 0.037e-3})
      for (double depth : {0.05e-3, 0.1e-3, 0.2e-3, 0.3e-3, 0.6e-3}) {
        Rig rig(slab(), r);
        const glm::dvec3 at(x, kTool.tipRadius - depth, 0.013e-3);
        rig.approach(tilted(at + glm::dvec3(0, 1.5e-3, 0), tilt), tilted(at, tilt));
        bool settled = false;
        const auto out = rig.settle(tilted(at, tilt), settled);
        ASSERT_TRUE(settled);
        ASSERT_GT(out.force.y, 0.0) << "tilt " << tilt << " x " << x << " depth " << depth;
        EXPECT_LE(std::hypot(out.force.x, out.force.z), 0.05 * out.force.y)
            << "tilt " << tilt << " x " << x << " depth " << depth;
      }
}

// Must hold (issue 14): on a ball the force is within 3° of the normal.
TEST(LineProxy, OnABallTheForceIsWithinThreeDegreesOfTheNormal) {
  const double R = 2.0e-3;
  LineProxyRenderer r;
  Rig rig(analytic(64, [&](const glm::dvec3& p) { return glm::length(p) - R; }), r);
  for (const glm::dvec3 d : {glm::dvec3(0.3, 1.0, 0.2), glm::dvec3(0.4, 1.0, -0.3), glm::dvec3(-0.7, 0.6, 0.1),
                             glm::dvec3(1.0, 0.2, 0.05)})
    for (double depth : {0.05e-3, 0.15e-3, 0.25e-3}) {
      const glm::dvec3 n = glm::normalize(d);
      const Pose pressed = vertical(n * (R + kTool.tipRadius - depth));
      rig.approach(vertical(n * (R + kTool.tipRadius + 1.0e-3)), pressed);
      // Held 200 frames: every frame within 3°, and at rest (a proxy that keeps
      // sliding would be felt as a vibration).
      HapticOutput out = rig.step(pressed), first = out;
      double worst = 0.0, drift = 0.0;
      for (int i = 0; i < 200; ++i) {
        out = rig.step(pressed);
        ASSERT_GT(glm::length(out.force), 0.0) << "n " << n.x << "," << n.y << "," << n.z << " depth " << depth;
        worst = std::max(worst, std::acos(std::clamp(glm::dot(glm::normalize(out.force), n), -1.0, 1.0)) * 180.0 / M_PI);
        drift = std::max(drift, glm::length(out.force - first.force));
      }
      EXPECT_LE(worst, 3.0) << "n " << n.x << "," << n.y << "," << n.z << " depth " << depth;
      EXPECT_LE(drift, 5e-3 * glm::length(first.force)) << "n " << n.x << "," << n.y << "," << n.z << " depth " << depth;
    }
}

// #1's burr slides against BurrField::contactNormal: with the burr just
// touching a voxelised ball (where its proxy rests), the normal is within 2°
// RMS of the true one over 100 random directions, and under half as far off
// as the maximiser of the sampled field it starts from; in a bowl, a quarter
// nearer than the maximiser.
TEST(BurrField, WhereTheBurrTouchesABallTheContactNormalIsWithinTwoDegreesRms) {
  auto degreesBetween = [](const glm::dvec3& a, const glm::dvec3& b) {
    return std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0, 1.0)) * 180.0 / M_PI;
  };
  const double R = 2.0e-3, r = kTool.tipRadius;
  for (const bool bowl : {false, true}) {
    VoxelVolume volume = analytic(80, [&](const glm::dvec3& p) { return bowl ? R - glm::length(p) : glm::length(p) - R; });
    VoxelScene scene;
    scene.addVolume(volume, glm::dmat4(1.0), kIso);
    std::mt19937 random(7);
    std::normal_distribution<double> gauss;
    double squares = 0.0, maximiserSquares = 0.0;
    const int count = 100;
    for (int i = 0; i < count; ++i) {
      const glm::dvec3 d = glm::normalize(glm::dvec3(gauss(random), gauss(random), gauss(random)));
      const glm::dvec3 centre = (bowl ? R - r : R + r) * d, outward = bowl ? -d : d;  // the burr touching
      BurrField field(r);
      field.bind(scene);
      const double off = degreesBetween(field.contactNormal(centre), outward);
      const double maximiser = degreesBetween(-field.deepestDirection(), outward);
      squares += off * off, maximiserSquares += maximiser * maximiser;
    }
    const double rms = std::sqrt(squares / count), maximiserRms = std::sqrt(maximiserSquares / count);
    std::cout << (bowl ? "bowl" : "ball") << ": contact normal " << rms << " degrees RMS, maximiser " << maximiserRms << "\n";
    if (!bowl) {
      EXPECT_LE(rms, 2.0);
      EXPECT_LE(rms, 0.5 * maximiserRms);
    } else {
      // In the bowl the sampled peak often looks flatter than it is, and the
      // fit fades out there (ProxyPoint.cpp): measured 4.0 against 6.0.
      EXPECT_LE(rms, 0.75 * maximiserRms);
    }
  }
}

// BurrField's search at fine voxels: a burr 1 voxel into a plane, whatever
// the plane's normal, is felt (g > 0) at 12.5 µm voxels, 200 random normals.
// The 26 cube directions alone leave gaps where the 0.5 mm burr sags 0.11 r =
// 4.4 voxels below them, and s sees only half a voxel out of the surface.
// At the paper's 0.1 mm the 26 suffice for the burrs of the suite and the
// lesson (0.5 and 0.6 mm), so nothing changes there.
TEST(BurrField, AtFineVoxelsNoMaterialHidesBetweenTheSearchDirections) {
  const double r = kTool.tipRadius, scale = 0.125;  // 0.1 mm voxels shown at an eighth: 12.5 µm
  std::mt19937 random(11);
  std::normal_distribution<double> gauss;
  int missed = 0;
  std::size_t directions = 0;
  for (int i = 0; i < 200; ++i) {
    const glm::dvec3 n = glm::normalize(glm::dvec3(gauss(random), gauss(random), gauss(random)));
    VoxelVolume volume = analytic(48, [&](const glm::dvec3& p) { return glm::dot(p, n); });
    VoxelScene scene;
    scene.addVolume(volume, glm::scale(glm::dmat4(1.0), glm::dvec3(scale)), kIso);
    ASSERT_NEAR(scene.voxelSize(), 12.5e-6, 1e-12);
    BurrField field(r);
    field.bind(scene);
    directions = field.fineDirections();
    missed += !(field.value(n * (r - scene.voxelSize())) > 0.0);
  }
  EXPECT_EQ(missed, 0) << "of 200 planes 1 voxel into the burr, unfelt; " << directions << " fine directions";
  VoxelVolume volume = slab();
  VoxelScene paper;
  paper.addVolume(volume, glm::dmat4(1.0), kIso);
  for (const double radius : {0.5e-3, 0.6e-3}) {
    BurrField field(radius);
    field.bind(paper);
    EXPECT_EQ(field.fineDirections(), 0u) << "at 0.1 mm voxels, a burr of " << radius * 1e3 << " mm";
  }
}

// And in the physical suite: the hole, where the burr meets the rim on its
// way in, is felt at 25 µm as well as at 0.1 mm (37.9 % both, from the
// tilted poses' shaft, which the default's capped shares leave out: see the
// test below). Before the fine search: 92.7 % at 25 µm, the burr caught on
// the rim 1 mm above where a rigid tool rests.
TEST(LineProxy, AtFineVoxelsTheBurrIsNotCaughtOnTheHolesRim) {
  measure::PhysicalConfig hole;
  hole.scenes = {"hole"};
  const auto paper = measure::measurePhysical({"LineProxyRenderer", {}}, 0.1e-3, hole);
  const auto fine = measure::measurePhysical({"LineProxyRenderer", {}}, 0.025e-3, hole);
  ASSERT_FALSE(paper.empty());
  ASSERT_FALSE(fine.empty());
  EXPECT_LE(fine.back().forceRms, paper.back().forceRms + 0.01) << "hole: force RMS at 25 µm against 0.1 mm";
  EXPECT_LE(fine.back().drawnRms * 0.025, paper.back().drawnRms * 0.1 + 0.05) << "hole: drawn tool off (mm)";
}

// holdWholeTool: the burr's proxy keeps the shaft out too, so a tool wedged
// in a drilled hole (the burr on the wall, the shaft on the far rim) is lifted
// as a rigid tool held at the device's orientation is: issue 14's 5 % on the
// physical suite's hole (1.1 % measured; 37.8 % with the default's capped
// shares), and the rest of the suite within it as well (3.4 %).
TEST(LineProxy, HoldingTheWholeToolLiftsAToolWedgedInAHoleAsARigidToolIs) {
  const measure::RendererSpec spec{"LineProxyRenderer", {{"holdWholeTool", "true"}}};
  measure::PhysicalConfig hole;
  hole.scenes = {"hole"};
  const auto holeRows = measure::measurePhysical(spec, 0.1e-3, hole);
  ASSERT_FALSE(holeRows.empty());
  EXPECT_EQ(holeRows.back().missed, 0.0);
  EXPECT_LT(holeRows.back().forceRms, 0.05) << "hole: force RMS against the rigid tool";
  EXPECT_LT(holeRows.back().directionRms, 3.0) << "hole: degrees RMS";
  const auto all = measure::measurePhysical(spec, 0.1e-3);
  EXPECT_LT(all.back().forceRms, 0.05) << "all scenes: force RMS against the rigid tool";
}

// holdWholeTool's plane and joint projection on bad input: a tool tilted
// into a hole just wider than its burr (the shaft on the rim, a wedge), then
// NaN, a flip, a jump of thousands of voxels and back into the wedge: every
// output finite. (Back from the jump the proxy is held where the straight
// way back entered the slab, hundreds of newtons off, as a god object that
// cannot tunnel is; the safety layer clamps what reaches a device.)
TEST(LineProxy, HoldingTheWholeToolNeverGivesNonFiniteOutput) {
  const auto node = measure::makeRenderer({"LineProxyRenderer", {{"holdWholeTool", "true"}}});
  const double hole = 0.65e-3;  // the burr's radius is 0.5 mm
  Rig rig(analytic(64, [&](const glm::dvec3& p) { return std::max(p.y, hole - std::hypot(p.x, p.z)); }), *node);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  rig.approach(tilted({0, 2e-3, 0}, 0.35), tilted({-0.2e-3, -1.2e-3, 0}, 0.35));
  const Pose poses[] = {
      tilted({-0.3e-3, -1.3e-3, 0}, 0.4),  // deeper into the wedge
      vertical({nan, 0, 0}),
      Pose{{0, -1e-3, 0}, glm::dquat(nan, 0, 0, 0)},
      Pose{{0, -1e-3, 0}, glm::angleAxis(M_PI, glm::dvec3(1, 0, 0))},  // a 180° flip in the hole
      vertical({0.3, -0.2, 0.1}),                                       // a jump of thousands of voxels
      tilted({-0.3e-3, -1.3e-3, 0}, 0.4),                               // straight back into the wedge
      tilted({-0.3e-3, -1.3e-3, 0}, 0.4),
  };
  bool first = true;
  for (const Pose& p : poses) {
    const auto out = rig.step(p);
    EXPECT_TRUE(finite(out));
    if (first) {
      EXPECT_EQ(out.contacts, 2) << "the burr on the wall and the shaft on the rim: the wedge";
    }
    first = false;
  }
}

TEST(LineProxy, AFastPushDoesNotCarryTheProxyThroughAThinPlate) {
  LineProxyRenderer r;
  // A plate two voxels thick around y = 0.
  Rig rig(analytic(64, [](const glm::dvec3& p) { return std::abs(p.y) - kH; }), r);
  rig.algorithm->reset(vertical({0, 1e-3, 0}));
  rig.step(vertical({0, 1e-3, 0}));
  auto out = rig.step(vertical({0, -1.5e-3, 0}));  // 25 voxels in one frame, straight through
  ASSERT_TRUE(out.hasProxy);
  EXPECT_GT(out.proxy.y, 0.5 * kH);  // held on top of the plate
  EXPECT_GT(out.force.y, 0.0);
}

TEST(LineProxy, ProxySlidesAlongTheSurface) {
  LineProxyRenderer r;
  Rig rig(slab(), r);
  rig.approach(vertical({0, 1e-3, 0}), vertical({0, -0.2e-3, 0}));
  HapticOutput out;
  for (int i = 1; i <= 40; ++i) out = rig.step(vertical({i * 0.02e-3, -0.2e-3, 0}));
  EXPECT_NEAR(out.proxy.x, 0.8e-3, 0.1 * kH);
  EXPECT_NEAR(out.proxy.y, kTool.tipRadius, 0.2 * kH);  // the burr's centre, its surface on the slab
  EXPECT_LT(std::abs(out.force.x), 0.05 * out.force.y);  // frictionless
}

// Algorithm #2's own tests: SurfacePointTest.cpp.

// ---- switching renderers at run time ---------------------------------------------

TEST(RendererSwitch, FadesFromTheOldOutputToTheNewWithoutAJolt) {
  LineProxyRenderer one;
  SurfacePointRenderer two;
  VoxelVolume v = slab();
  VoxelScene scene;
  scene.addVolume(v, glm::dmat4(1.0), kIso);
  const Pose pressed = vertical({0, -0.2e-3, 0});
  auto first = one.compile(kTool, scene);
  first->reset(vertical({0, 1e-3, 0}));
  for (int i = 0; i <= 20; ++i) first->step(scene, {vertical({0, 1e-3 - i * 0.06e-3, 0}), 1e-3});
  RendererSwitch sw(std::move(first), 0.05);
  const HapticOutput before = sw.step(scene, {pressed, 1e-3});
  sw.replace(two.compile(kTool, scene), pressed);
  glm::dvec3 last = before.force;
  double biggestJump = 0.0;
  HapticOutput out;
  for (int i = 0; i < 80; ++i) {
    out = sw.step(scene, {pressed, 1e-3});
    biggestJump = std::max(biggestJump, glm::length(out.force - last));
    last = out.force;
  }
  EXPECT_FALSE(sw.fading());
  EXPECT_TRUE(sw.takeRetired() != nullptr);
  // 50 frames of fade: no frame changes the force by more than 1/50 of the
  // difference between the two renderers (plus a little for #2 settling).
  const double difference = glm::length(out.force - before.force);
  ASSERT_GT(difference, 0.0);
  EXPECT_LT(biggestJump, difference / 50.0 * 1.5 + 1e-6);
}
