// Issue 47: the phantom's pulp is a soft tissue (below the default lesson's
// isoValue): there is nothing of it to remove, so the lesson's ForbiddenRegion
// is violated when the burr's head enters it. For every renderer in the
// registry, the default lesson's over-drill (a plunge down the tooth's axis)
// is flagged within one burr radius of travel of the geometric entry, computed
// here from the drawn burr and the phantom's own voxels; a plunge that stops
// 0.3 mm short is not flagged. And the region outputs reach the lesson's
// routes in a replay stopped before and after the entry (what `render --at`
// draws).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "measure/Renderers.h"
#include "millsim/core/NodeRegistry.h"
#include "millsim/lesson/ForbiddenRegion.h"
#include "millsim/lesson/MillingTarget.h"
#include "millsim/session/Replay.h"
#include "millsim/std/Switch.h"
#include "millsim/std/Text.h"
#include "millsim/volume/TissueMap.h"
#include "millsim/volume/VolumeIO.h"
#include "millsim/volume/ToothPhantom.h"
#include "millsim/volume/VolumeObject.h"
#include "millsim/x3d/X3DLoader.h"

using namespace millsim;
namespace fs = std::filesystem;

namespace {

const fs::path kSource = MILLSIM_SOURCE_DIR;
constexpr double kTipRadius = 0.6e-3;  // the default lesson's burr

// Down the tooth's axis: above the crown at 10.5 mm, milling from 9.5 mm at
// 1 s, down to `bottom` (m) at 10 s, held there half a second.
Trajectory plunge(double bottom) {
  const glm::dquat up(1, 0, 0, 0);
  return Trajectory({{0.0, Pose{{0, 0.0105, 0}, up}, false},
                     {1.0, Pose{{0, 0.0095, 0}, up}, true},
                     {10.0, Pose{{0, bottom, 0}, up}, true},
                     {10.5, Pose{{0, bottom, 0}, up}, true}});
}

struct Plunged {
  std::vector<double> t;
  std::vector<glm::dvec3> drawn;  // the burr centre as drawn, frame by frame
  bool violated = false;
  double flagged = -1.0, depth = 0.0, swept = 0.0;
  // The first frame whose drawn head holds a pulp voxel below the isoValue
  // (-1: none), and the head's closest approach to one (m, from its surface).
  long entry = -1;
  double closest = std::numeric_limits<double>::infinity();
};

Plunged plungeDefaultLesson(const std::string& renderer, double bottom) {
  Plunged p;
  LoadResult r = loadSceneFile((kSource / "x3d/default.x3d").string(), builtinRegistry());
  EXPECT_TRUE(r.ok()) << r.report();
  if (!r.ok()) return p;
  ReplayOptions options;
  options.renderer = renderer;
  options.onFrame = [&](const FrameRecord& f) {
    p.t.push_back(f.t);
    p.drawn.push_back(f.out.drawnTool.position);
  };
  replay(*r.scene, plunge(bottom), nullptr, options);
  const ForbiddenRegion& pulp = *r.scene->nodesOfType<ForbiddenRegion>().front();
  p.violated = pulp.violated.get();
  p.flagged = pulp.firstViolationTime.get().seconds;
  p.depth = pulp.depth.get();
  p.swept = pulp.sweptVolume.get();

  // The pulp's soft voxels from the phantom itself (its labels, its original
  // densities), near the axis the burr travels down: the lesson's volume sits
  // at the scene's origin, untransformed.
  const VolumeObject& tooth = *r.scene->nodesOfType<VolumeObject>().front();
  const VoxelVolume fresh = makeToothPhantom(ToothPhantomOptions{});
  const VoxelVolume labels = makeToothPhantomLabels(ToothPhantomOptions{});
  std::vector<glm::dvec3> pulpVoxels;
  for (auto it = labels.grid().cbeginValueOn(); it; ++it) {
    const openvdb::Coord c = it.getCoord();
    if (std::lround(*it) != kToothPulp || !(fresh.valueAt(c.x(), c.y(), c.z()) < tooth.isoValue.get())) continue;
    const glm::dvec3 at = fresh.indexToLocal(glm::dvec3(c.x(), c.y(), c.z()));
    if (std::hypot(at.x, at.z) < kTipRadius + 0.5e-3) pulpVoxels.push_back(at);
  }
  EXPECT_GT(pulpVoxels.size(), 100u) << "no pulp voxels below the isoValue near the tooth's axis";
  for (std::size_t i = 0; i < p.drawn.size(); ++i) {
    double nearest = std::numeric_limits<double>::infinity();
    for (const glm::dvec3& v : pulpVoxels) nearest = std::min(nearest, glm::length(v - p.drawn[i]));
    p.closest = std::min(p.closest, nearest - kTipRadius);
    if (p.entry < 0 && nearest <= kTipRadius) p.entry = long(i);
  }
  return p;
}

class EveryRendererOverDrills : public ::testing::TestWithParam<std::string> {};

TEST_P(EveryRendererOverDrills, ThePulpIsFlaggedWithinABurrRadiusOfItsEntry) {
  const Plunged p = plungeDefaultLesson(GetParam(), 0.0045);
  ASSERT_GE(p.entry, 0) << "the plunge never brought the drawn burr into the pulp";
  ASSERT_TRUE(p.violated) << "the burr entered the pulp at " << p.t[std::size_t(p.entry)] << " s; not flagged";
  // Where the burr was when it was flagged, against where it entered.
  const auto at = std::lower_bound(p.t.begin(), p.t.end(), p.flagged - 1e-9);
  ASSERT_NE(at, p.t.end());
  const double travel = glm::length(p.drawn[std::size_t(at - p.t.begin())] - p.drawn[std::size_t(p.entry)]);
  EXPECT_LE(travel, kTipRadius) << "entered at " << p.t[std::size_t(p.entry)] << " s, flagged at " << p.flagged
                                << " s, " << travel * 1e3 << " mm of travel later";
  // No deeper than the burr went on from where it first touched (and a voxel).
  const double onward = p.drawn[std::size_t(p.entry)].y - p.drawn.back().y;
  EXPECT_GT(p.depth, 0.0);
  EXPECT_LE(p.depth, onward + 0.1e-3) << "the burr went " << onward * 1e3 << " mm on from its entry";
  EXPECT_GT(p.swept, 0.0);
}

TEST_P(EveryRendererOverDrills, APlungeThatStopsShortIsNotFlagged) {
  // Where the burr's head first holds a pulp voxel on the way down, plus 0.3 mm.
  const Plunged through = plungeDefaultLesson(GetParam(), 0.0045);
  ASSERT_GE(through.entry, 0);
  const double bottom = through.drawn[std::size_t(through.entry)].y + 0.3e-3;
  const Plunged shy = plungeDefaultLesson(GetParam(), bottom);
  EXPECT_GT(shy.closest, 0.2e-3) << "the short plunge's burr came within " << shy.closest * 1e3
                                 << " mm of the pulp (the path is not short)";
  EXPECT_FALSE(shy.violated) << "stopped " << shy.closest * 1e3 << " mm short of the pulp, flagged at " << shy.flagged
                             << " s";
  EXPECT_EQ(shy.depth, 0.0);
  EXPECT_EQ(shy.swept, 0.0);
}

// A soft tissue the burr enters without cutting anything: an exposed canal
// (0.8 mm in radius, open at the surface of a dentin slab, y < 0, 2 mm deep)
// that a burr (0.5 mm) not spinning is pushed down into. Nothing is removed,
// so only the entry can flag it.
TEST_P(EveryRendererOverDrills, ABurrNotCuttingIsFlaggedWhenItEntersASoftTissue) {
  constexpr int n = 64;
  constexpr double h = 0.1e-3, radius = 0.8e-3;
  std::vector<float> density(std::size_t(n) * n * n), label(density.size());
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const glm::dvec3 p = (glm::dvec3(i, j, k) - 0.5 * (n - 1)) * h;
        const std::size_t v = (std::size_t(k) * n + j) * n + i;
        const bool soft = std::hypot(p.x, p.z) < radius && p.y > -2.0e-3 && p.y < 0.0;
        density[v] = soft ? 40.f : float(1600.0 * std::clamp(0.5 - p.y / h, 0.0, 1.0));
        label[v] = soft ? 3.f : density[v] > 0.f ? 2.f : 0.f;
      }
  const fs::path dir = fs::temp_directory_path() / ("millsim-soft-" + GetParam());
  fs::create_directories(dir);
  writeNrrd(VoxelVolume::fromDense(density.data(), {n, n, n}, glm::dvec3(h), 0.f), dir / "slab.nrrd");
  writeNrrd(VoxelVolume::fromDense(label.data(), {n, n, n}, glm::dvec3(h), 0.f), dir / "labels.nrrd");
  const std::string scene = R"(<X3D><Scene>
  <VolumeObject url='")" + (dir / "slab.nrrd").string() + R"("' labelUrl='")" + (dir / "labels.nrrd").string() +
                            R"("' isoValue="700" airValue="0">
    <Tissue name="dentin" label="2"/><Tissue name="canal" label="3" soft="true"/>
  </VolumeObject>
  <ForbiddenRegion DEF="Canal" name="canal" tissues='"canal"'/>
  <HandDevice><MillTool tipRadius="0.0005" shaftRadius="0.0003" shaftLength="0.01"/><SurfacePointRenderer/></HandDevice>
</Scene></X3D>)";
  LoadResult r = loadSceneString(scene, (dir / "soft.x3d").string(), builtinRegistry());
  ASSERT_TRUE(r.ok()) << r.report();
  const glm::dquat up(1, 0, 0, 0);
  const Trajectory down({{0.0, Pose{{0, 1.0e-3, 0}, up}, false},
                         {2.0, Pose{{0, -1.0e-3, 0}, up}, false},
                         {2.5, Pose{{0, -1.0e-3, 0}, up}, false}});
  ReplayOptions options;
  options.renderer = GetParam();
  std::vector<glm::dvec3> drawn;
  std::vector<double> times;
  options.onFrame = [&](const FrameRecord& f) {
    drawn.push_back(f.out.drawnTool.position);
    times.push_back(f.t);
  };
  replay(*r.scene, down, nullptr, options);
  // Geometric entry: the head's surface reaches the canal's first voxel centre.
  std::size_t entry = drawn.size();
  for (std::size_t i = 0; i < drawn.size() && entry == drawn.size(); ++i)
    for (int k = 0; k < n && entry == drawn.size(); ++k)
      for (int j = 0; j < n && entry == drawn.size(); ++j)
        for (int i2 = 0; i2 < n; ++i2) {
          const glm::dvec3 p = (glm::dvec3(i2, j, k) - 0.5 * (n - 1)) * h;
          if (std::hypot(p.x, p.z) < radius && p.y > -2.0e-3 && p.y < 0.0 && glm::length(p - drawn[i]) <= 0.5e-3) {
            entry = i;
            break;
          }
        }
  ASSERT_LT(entry, drawn.size()) << "the burr never reached the canal";
  const ForbiddenRegion& canal = *r.scene->nodesOfType<ForbiddenRegion>().front();
  EXPECT_EQ(canal.removedVolume.get(), 0.f) << "a burr not spinning removed something";
  ASSERT_TRUE(canal.violated.get()) << "the burr entered the canal at " << times[entry] << " s; not flagged";
  const auto at = std::lower_bound(times.begin(), times.end(), canal.firstViolationTime.get().seconds - 1e-9);
  ASSERT_NE(at, times.end());
  EXPECT_LE(glm::length(drawn[std::size_t(at - times.begin())] - drawn[entry]), 0.5e-3)
      << "entered at " << times[entry] << " s, flagged at " << canal.firstViolationTime.get().seconds << " s";
  EXPECT_GT(canal.depth.get(), 0.5e-3) << "the head went a millimetre into the canal";
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Algorithms, EveryRendererOverDrills, ::testing::ValuesIn(measure::registeredRenderers()),
                         [](const ::testing::TestParamInfo<std::string>& p) { return p.param; });

// The lesson's own routes show the violation and the cavity's progress in a
// replay stopped at a time, as `millsim render --at` draws it.
TEST(RegionRoutes, AReplayStoppedAtATimeShowsTheRegionsThroughTheLessonsRoutes) {
  const auto at = [](double until) {
    LoadResult r = loadSceneFile((kSource / "tests/data/lessons/region-routes.x3d").string(), builtinRegistry());
    EXPECT_TRUE(r.ok()) << r.report();
    ReplayOptions options;
    options.until = until;
    replay(*r.scene, plunge(0.0045), nullptr, options);
    const auto* done = dynamic_cast<const Text*>(r.scene->def("Done").get());
    const auto* warning = dynamic_cast<const Switch*>(r.scene->def("Warning").get());
    EXPECT_TRUE(done && warning);
    return std::make_pair(done ? done->string.get().front() : std::string(), warning ? warning->whichChoice.get() : -2);
  };
  const auto before = at(5.0), after = at(10.5);
  EXPECT_NE(before.first, "cavity 0 % done") << "the target's fraction did not reach the Text";
  EXPECT_EQ(before.second, -1) << "the pulp warning shows before the burr reached the pulp";
  EXPECT_EQ(after.second, 0) << "the pulp warning is not shown after the burr went into the pulp";
}

}  // namespace
