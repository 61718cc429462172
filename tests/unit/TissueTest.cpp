// Lessons: tissues — which material each voxel is (TissueMap), the phantom's
// labels, hardness (how fast each renderer's burr cuts a tissue under the
// same hand; docs/algorithms.md, "Tissue hardness") — and the assessment
// regions a lesson reports on (docs/lessons.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "measure/Renderers.h"
#include "millsim/haptics/CutFront.h"
#include "millsim/core/NodeRegistry.h"
#include "millsim/lesson/ForbiddenRegion.h"
#include "millsim/lesson/MillingTarget.h"
#include "millsim/lesson/RegionAccounting.h"
#include "millsim/session/LessonReport.h"
#include "millsim/session/Replay.h"
#include "millsim/volume/VolumeObject.h"
#include "millsim/x3d/X3DLoader.h"
#include "millsim/devices/HandDevice.h"
#include "millsim/run/HapticLoop.h"
#include "millsim/volume/Tissue.h"
#include "millsim/volume/TissueMap.h"
#include "millsim/volume/ToothPhantom.h"
#include "millsim/volume/VoxelScene.h"
#include "AnalyticScenes.h"
#include "TestFiles.h"
#include "millsim/volume/VolumeIO.h"

using namespace millsim;
using namespace millsim::test;

namespace {

std::shared_ptr<Tissue> tissue(const std::string& name, glm::vec2 range, float hardness) {
  auto t = std::make_shared<Tissue>();
  t->name.set(name);
  t->densityRange.set(range);
  t->hardness.set(hardness);
  return t;
}

// Material removed in `seconds` by a hand that holds the spinning burr on a
// slab whose material is one tissue of the given hardness, aiming 2 mm below
// (about 1 N of grip): short enough that neither reaches the aim.
double removedPressingInto(const std::string& renderer, float hardness, double seconds) {
  VoxelVolume volume = slab();
  const auto t = tissue("test", {1.f, 2000.f}, hardness);
  const auto map = TissueMap::build(volume, {t.get()}, nullptr);
  VoxelScene scene;
  scene.addVolume(volume, glm::dmat4(1.0), kIso, nullptr, map.get());
  const glm::dquat up(1, 0, 0, 0);
  const double aim = kTool.tipRadius - 2e-3;
  const Trajectory hand({{0.0, Pose{{0, kTool.tipRadius, 0}, up}, true},
                         {0.001, Pose{{0, aim, 0}, up}, true},
                         {seconds + 1.0, Pose{{0, aim, 0}, up}, true}});
  LoopSettings s;
  s.timing = false;
  s.logCapacity = 4;
  s.tool = kTool;
  const auto node = measure::makeRenderer({renderer, {}});
  HapticLoop loop(scene, node->compile(kTool, scene), makeHandDriver(hand, HandModel{}, false), s);
  for (long n = 0; n < long(seconds * 1000); ++n) {
    loop.stepSimulated();
    loop.records().drain([](const FrameRecord&) {});
  }
  return loop.stats().removedVolume;
}

}  // namespace

TEST(TissueMap, ClassifiesByOriginalDensityFirstMatchWins) {
  // A slab whose surface falls between voxel centres: one row of 200s.
  VoxelVolume volume = analytic(64, [](const glm::dvec3& p) { return p.y - 0.02e-3; });
  const auto soft = tissue("soft", {1.f, 600.f}, 0.5f), hard = tissue("hard", {400.f, 2000.f}, 3.f);
  const auto map = TissueMap::build(volume, {soft.get(), hard.get()}, nullptr);
  ASSERT_EQ(map->entries().size(), 3u);
  EXPECT_EQ(map->find("hard"), 2);
  EXPECT_EQ(map->find("none"), 0);
  // Deep in the slab (density 1000): hard; the surface ramp at 500 matches soft first.
  EXPECT_EQ(map->labelAt(32, 10, 32), 2);
  int rampLabel = -1;
  for (int j = 0; j < 64; ++j)
    if (volume.valueAt(32, j, 32) > 1.f && volume.valueAt(32, j, 32) < 600.f) rampLabel = map->labelAt(32, j, 32);
  EXPECT_EQ(rampLabel, 1);
  EXPECT_EQ(map->labelAt(32, 60, 32), 0);  // air
  EXPECT_GT(map->voxelCounts()[2], 64u * 64u * 20u);
}

TEST(TissueMap, ChoosesByLabelAndRefusesAMismatchedLabelVolume) {
  ToothPhantomOptions o;
  o.dims = {64, 64, 44};
  o.voxelSize = 0.4e-3;
  const VoxelVolume density = makeToothPhantom(o);
  const VoxelVolume labels = makeToothPhantomLabels(o);
  auto enamel = std::make_shared<Tissue>(), pulp = std::make_shared<Tissue>();
  enamel->name.set("enamel");
  enamel->label.set(kToothEnamel);
  pulp->name.set("pulp");
  pulp->label.set(kToothPulp);
  const auto map = TissueMap::build(density, {enamel.get(), pulp.get()}, &labels);
  EXPECT_GT(map->voxelCounts()[1], 100u);
  EXPECT_GT(map->voxelCounts()[2], 10u);
  // Every voxel with material in the density volume has a phantom label.
  std::uint64_t unlabelled = 0;
  for (auto v = density.grid().cbeginValueOn(); v; ++v)
    unlabelled += labels.grid().tree().getValue(v.getCoord()) < 0.5f;
  EXPECT_EQ(unlabelled, 0u);

  ToothPhantomOptions other = o;
  other.dims = {32, 32, 22};
  const VoxelVolume wrong = makeToothPhantomLabels(other);
  try {
    TissueMap::build(density, {enamel.get()}, &wrong);
    FAIL() << "a label volume of another size was accepted";
  } catch (const VolumeError& e) {
    EXPECT_NE(std::string(e.what()).find("32x32x22"), std::string::npos) << e.what();
  }
  EXPECT_THROW(TissueMap::build(density, {enamel.get()}, nullptr), VolumeError);
}

// The map is built leaf by leaf on TBB's threads, the counts summed per chunk
// of leaves: every material voxel is classified once, as one serial walk does
// (the phantom at 0.1 mm spans thousands of leaves; tissues by label and by
// density, first match wins).
TEST(TissueMap, TheParallelBuildClassifiesEveryVoxelOnce) {
  const ToothPhantomOptions o;
  const VoxelVolume density = makeToothPhantom(o), labels = makeToothPhantomLabels(o);
  std::vector<std::shared_ptr<Tissue>> owned;
  for (int label : {kToothEnamel, kToothDentin, kToothPulp}) {
    owned.push_back(std::make_shared<Tissue>());
    owned.back()->name.set("label " + std::to_string(label));
    owned.back()->label.set(label);
  }
  owned.push_back(tissue("by density", {-999.f, 2000.f}, 1.f));  // what no label took (cementum)
  std::vector<const Tissue*> list;
  for (const auto& t : owned) list.push_back(t.get());
  const float iso = 700.f;
  const auto map = TissueMap::build(density, list, &labels, iso);
  std::vector<std::uint64_t> counts(list.size() + 1, 0), below(list.size() + 1, 0);
  std::vector<double> belowSum(list.size() + 1, 0.0);
  auto l = labels.grid().getConstAccessor();
  for (auto v = density.grid().cbeginValueOn(); v; ++v) {
    const int label = int(std::lround(l.getValue(v.getCoord())));
    std::size_t entry = 0;
    for (std::size_t t = 0; t < 3 && entry == 0; ++t) entry = label == list[t]->label.get() ? t + 1 : 0;
    if (entry == 0 && *v >= -999.f && *v < 2000.f) entry = 4;
    ++counts[entry];
    if (*v < iso) ++below[entry], belowSum[entry] += *v;
    ASSERT_EQ(map->labelAt(v.getCoord().x(), v.getCoord().y(), v.getCoord().z()), int(entry)) << v.getCoord();
  }
  ASSERT_GT(density.grid().tree().leafCount(), 1000u);
  EXPECT_EQ(map->voxelCounts(), counts);
  EXPECT_EQ(map->belowSurfaceCounts(), below);
  EXPECT_GT(counts[4], 1000u) << "the density tissue took the cementum";
  for (std::size_t e = 1; e < counts.size(); ++e) {
    if (below[e] > 0) {
      EXPECT_NEAR(map->entries()[e].densityBelowSurface, belowSum[e] / double(below[e]), 1e-3) << e;
    }
  }
}

// Label files are read on another thread while the densities are: the same
// tissues as the phantom's own labels give, and a labelUrl list none of whose
// volumes loads is still one error naming every url and why.
TEST(TissueMap, LabelFilesReadAheadGiveTheSameTissuesAndTheSameErrors) {
  millsim::test::ScratchDir dir;
  const ToothPhantomOptions o{{64, 64, 44}, 0.4e-3, false};
  writeNrrd(makeToothPhantom(o), dir.path() / "tooth.nrrd");
  writeNrrd(makeToothPhantomLabels(o), dir.path() / "labels.nrrd");
  auto scene = [&](const std::string& url, const std::string& labelUrl) {
    return millsim::test::x3d("<VolumeObject url='" + url + "' labelUrl='" + labelUrl + "' isoValue='700'>"
                              "<Tissue name='enamel' label='1'/><Tissue name='dentin' label='2'/>"
                              "<Tissue name='pulp' label='3'/></VolumeObject>");
  };
  auto counts = [](const LoadResult& r) {
    const auto* map = r.scene->nodesOfType<VolumeObject>().front()->tissueMap();
    return map ? map->voxelCounts() : std::vector<std::uint64_t>{};
  };
  const LoadResult files = loadSceneString(scene("\"tooth.nrrd\"", "\"labels.nrrd\""), (dir.path() / "a.x3d").string(),
                                           builtinRegistry());
  ASSERT_TRUE(files.ok()) << files.report();
  const LoadResult phantom = loadSceneString(
      scene("\"phantom:tooth?size=64,64,44&amp;voxel=0.0004\"", "\"phantom:tooth-labels?size=64,64,44&amp;voxel=0.0004\""),
      (dir.path() / "b.x3d").string(), builtinRegistry());
  ASSERT_TRUE(phantom.ok()) << phantom.report();
  EXPECT_EQ(counts(files), counts(phantom));
  EXPECT_GT(counts(files).at(3), 0u) << "the pulp";

  const LoadResult missing = loadSceneString(scene("\"tooth.nrrd\"", "\"gone.nrrd\" \"gone.vdb\""),
                                             (dir.path() / "c.x3d").string(), builtinRegistry());
  ASSERT_FALSE(missing.ok());
  const std::string report = missing.report();
  EXPECT_NE(report.find("VolumeObject could not load any of its labelUrl volumes:"), std::string::npos) << report;
  EXPECT_NE(report.find("gone.nrrd: no such file"), std::string::npos) << report;
  EXPECT_NE(report.find("gone.vdb: no such file"), std::string::npos) << report;
}

TEST(TissueMap, PhantomLabelUrlsCarryThePhantomsOptions) {
  EXPECT_TRUE(isPhantomLabelsUrl("phantom:tooth-labels?size=32,32,22"));
  EXPECT_FALSE(isPhantomLabelsUrl("phantom:tooth?size=32,32,22"));
  EXPECT_EQ(loadPhantomLabels("phantom:tooth-labels?size=32,32,22").dims(), glm::ivec3(32, 32, 22));
  try {
    loadPhantomLabels("phantom:tooth-labels?size=3,3");
    FAIL();
  } catch (const VolumeError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("phantom:tooth-labels?size=3,3: ", 0), 0u) << e.what();
  }
}

// The issue's contract: under the same hand, hardness 4 loses markedly less
// than hardness 1 in the same time, and hardness 0 is never cut — for every
// renderer in the registry.
TEST(TissueHardness, HarderTissueLosesLessUnderTheSameHandWithEveryRenderer) {
  const std::vector<std::string> types = measure::registeredRenderers();
  ASSERT_GE(types.size(), 3u);
  for (const std::string& name : types) {
    const double soft = removedPressingInto(name, 1.f, 0.1);
    const double hard = removedPressingInto(name, 4.f, 0.1);
    const double never = removedPressingInto(name, 0.f, 0.1);
    RecordProperty(name + "_removed_mm3_h1", std::to_string(soft * 1e9));
    RecordProperty(name + "_removed_mm3_h4", std::to_string(hard * 1e9));
    EXPECT_GT(soft, 0.01e-9) << name << ": the soft tissue was hardly cut";
    EXPECT_LT(hard, 0.6 * soft) << name << ": hardness 4 removed " << hard * 1e9 << " mm³, hardness 1 " << soft * 1e9;
    EXPECT_EQ(never, 0.0) << name << ": hardness 0 was cut";
  }
}

// ---- Assessment regions (MillingTarget, ForbiddenRegion) ----

namespace {

// The phantom at 0.2 mm, its tissues by label, a target over the occlusal
// surface and the pulp forbidden; a TrajectoryDevice puts the burr where the
// trajectory says.
const char* kRegionScene = R"(<X3D><Scene>
  <VolumeObject url='"phantom:tooth?size=128,128,88"' labelUrl='"phantom:tooth-labels?size=128,128,88"' isoValue="700">
    <Tissue name="enamel" label="1"/><Tissue name="dentin" label="2"/><Tissue name="pulp" label="3" hardness="0.05"/>
  </VolumeObject>
  <MillingTarget name="cavity"><Transform translation="0 0.0083 0">
    <Shape><Cylinder radius="0.0008" height="0.0025"/></Shape></Transform></MillingTarget>
  <ForbiddenRegion name="pulp" tissues='"pulp"'/>
  <TrajectoryDevice><MillTool tipRadius="0.0006" shaftRadius="0.0004" shaftLength="0.015"/><SurfacePointRenderer/></TrajectoryDevice>
</Scene></X3D>)";

struct RegionRun {
  std::unique_ptr<Scene> scene;
  std::vector<RegionResult> results;
  RemovalSummary summary;
  double removed = 0.0;  // m³: the whole run's, by the haptic loop's own count
  double end = 0.0;      // s: the last frame's time
};

// Straight down the tooth's axis from 12 mm to `bottom` (burr centre, m) in
// `seconds`, milling, replayed up to `until`.
RegionRun millDown(double bottom, double seconds, double until) {
  RegionRun run;
  LoadResult r = loadSceneString(kRegionScene, "regions.x3d", builtinRegistry());
  EXPECT_TRUE(r.ok()) << r.report();
  run.scene = std::move(r.scene);
  const glm::dquat up(1, 0, 0, 0);
  const Trajectory t({{0.0, Pose{{0, 0.012, 0}, up}, true},
                      {seconds, Pose{{0, bottom, 0}, up}, true},
                      {seconds + 0.5, Pose{{0, bottom, 0}, up}, true}});
  RegionAccounting regions(*run.scene);
  ReplayOptions options;
  options.until = until;
  options.onLoop = [&](HapticLoop& loop) {
    for (std::size_t i = 0; i < regions.volumeCount(); ++i) loop.publishBlocks(i, regions.channel(i));
  };
  options.onFrame = [&](const FrameRecord& f) {
    regions.update(f.t);
    run.end = f.t;
  };
  run.removed = replay(*run.scene, t, nullptr, options).stats.removedVolume;
  regions.publishFields();
  run.results = regions.results();
  run.summary = regions.summary();
  return run;
}

// What the burr removed from the pulp, counted over the whole volume against
// a fresh phantom: independent of the accounting's blocks.
double pulpRemovedRecount(const Scene& scene) {
  const VolumeObject& vo = *scene.nodesOfType<VolumeObject>().front();
  const VoxelVolume fresh = makeToothPhantom(parsePhantomUrl("phantom:tooth?size=128,128,88"));
  const TissueMap& map = *vo.tissueMap();
  const int pulp = map.find("pulp");
  const double air = vo.airValue.get(), scale = 1.0 / (2.0 * (vo.isoValue.get() - air));
  auto phi = [&](double v) { return std::clamp((v - air) * scale, 0.0, 1.0); };
  const glm::dvec3 h = fresh.voxelSize();
  double removed = 0.0;
  for (auto it = fresh.grid().cbeginValueOn(); it; ++it) {
    const openvdb::Coord c = it.getCoord();
    if (map.labelAt(c.x(), c.y(), c.z()) != pulp) continue;
    removed += std::max(0.0, phi(*it) - phi(vo.volume()->valueAt(c.x(), c.y(), c.z()))) * h.x * h.y * h.z;
  }
  return removed;
}

}  // namespace

TEST(Regions, MillingOnlyInsideTheTargetReportsAFractionAndNoViolation) {
  const RegionRun run = millDown(0.0078, 1.0, 1e9);
  ASSERT_EQ(run.results.size(), 2u);
  const RegionResult& cavity = run.results[0];
  const RegionResult& pulp = run.results[1];
  EXPECT_FALSE(cavity.forbidden);
  EXPECT_GT(cavity.initial, 3e-9);  // about π·0.8²·2.5 mm³ of enamel and dentin
  EXPECT_GT(cavity.fraction(), 0.1);
  EXPECT_LE(cavity.fraction(), 1.0);
  EXPECT_TRUE(pulp.forbidden);
  EXPECT_EQ(pulp.removed, 0.0);
  EXPECT_LT(pulp.firstViolation, 0.0);
  const auto* target = run.scene->nodesOfType<MillingTarget>().front();
  EXPECT_FLOAT_EQ(target->fraction.get(), float(cavity.fraction()));
  EXPECT_FALSE(run.scene->nodesOfType<ForbiddenRegion>().front()->violated.get());
}

TEST(Regions, GoingOnIntoThePulpReportsWhenItWasFirstCut) {
  const RegionRun deep = millDown(0.0035, 3.0, 1e9);
  const RegionResult& pulp = deep.results[1];
  ASSERT_GE(pulp.firstViolation, 0.0) << "the burr went 1.5 mm into the pulp and no violation was reported";
  // The blocks, counted as they were milled, agree with a whole-volume recount.
  EXPECT_NEAR(pulp.removed, pulpRemovedRecount(*deep.scene), 1e-3 * pulp.removed + 1e-15);
  const auto* node = deep.scene->nodesOfType<ForbiddenRegion>().front();
  EXPECT_TRUE(node->violated.get());
  EXPECT_DOUBLE_EQ(node->firstViolationTime.get().seconds, pulp.firstViolation);
  // The time is right within a few frames: nothing of the pulp was cut 3 ms
  // before it, something was 3 ms after (recounted, not by the accounting).
  EXPECT_EQ(pulpRemovedRecount(*millDown(0.0035, 3.0, pulp.firstViolation - 0.003).scene), 0.0);
  EXPECT_GT(pulpRemovedRecount(*millDown(0.0035, 3.0, pulp.firstViolation + 0.003).scene), 0.0);
}

// Issue 47, part 6: what a teacher grades beyond the regions. Milling 1.5 mm
// into the pulp removes material outside the cavity (dentin and pulp below
// it); the removal outside the target and the target's own add up to the
// whole, per tissue too, and to the haptic loop's own count of the run; the
// score counts the over-preparation by the target's penalty.
TEST(Regions, RemovalOutsideTheTargetAndPerTissueAddUpToTheWhole) {
  const RegionRun deep = millDown(0.0035, 3.0, 1e9);
  const RegionResult& cavity = deep.results[0];
  const RemovalSummary& s = deep.summary;
  ASSERT_TRUE(s.hasTargets);
  EXPECT_GT(s.outsideTargets, 0.5e-9) << "the burr went 3.6 mm below the cavity's floor";
  double tissues = 0.0, pulp = 0.0, dentin = 0.0;
  for (const auto& [name, removed] : s.byTissue) {
    tissues += removed;
    if (name == "pulp") pulp = removed;
    if (name == "dentin") dentin = removed;
  }
  EXPECT_NEAR(tissues, cavity.removed + s.outsideTargets, 1e-9 * tissues);
  EXPECT_NEAR(tissues, deep.removed, 1e-3 * deep.removed) << "the loop's own count of the run";
  EXPECT_NEAR(pulp, deep.results[1].removed, 1e-9 * pulp + 1e-18);
  EXPECT_GT(dentin, s.outsideTargets - pulp - 1e-12);  // below the cavity there is only dentin and pulp
  EXPECT_NEAR(s.targetsInitial, cavity.initial, 1e-12 * cavity.initial);
  EXPECT_DOUBLE_EQ(s.overPreparationPenalty, 1.0);
  // The score: the cavity's share, halved for the pulp, times (1 - penalty x outside / target).
  LessonReport report{"regions.x3d", "SurfacePointRenderer", deep.end, deep.removed, 0.0, 0.0, deep.results, s};
  const double base = 100.0 * std::min(1.0, cavity.fraction()) * 0.5;
  EXPECT_NEAR(lessonScore(report), base * std::max(0.0, 1.0 - s.overPreparation()), 1e-9);
  report.removal.overPreparationPenalty = 0.0;
  EXPECT_NEAR(lessonScore(report), base, 1e-9);
  // Done when the cavity reached completeAt (0.9), not before, and never past the run's end.
  if (cavity.fraction() >= 0.9) {
    EXPECT_GE(s.completed, 0.0);
    EXPECT_LE(s.completed, deep.end);
  } else {
    EXPECT_LT(s.completed, 0.0);
  }
  // A shallow cut inside the cavity removes nothing outside it.
  const RegionRun shallow = millDown(0.0078, 1.0, 1e9);
  EXPECT_LT(shallow.summary.outsideTargets, 0.02 * shallow.results[0].removed);
}

// The wall left over the pulp, against a brute-force recount: the least
// distance from a voxel cut through (φ ≤ ½ now, more before) to a pulp voxel,
// centre to centre, less the half voxel by which the pulp's surface lies
// outside its voxels' centres, agrees with the report to a voxel. A cut into
// the pulp leaves none; a shallow one more than 1.5 mm, or one farther than
// the wall is measured (kWallReach, 3 mm).
TEST(Regions, TheThinnestWallLeftOverThePulpIsReported) {
  const RegionRun medium = millDown(0.0060, 2.5, 1e9);
  const double wall = medium.results[1].thinnestWall;
  EXPECT_LT(medium.results[1].firstViolation, 0.0);
  ASSERT_GT(wall, 0.0);
  const VolumeObject& vo = *medium.scene->nodesOfType<VolumeObject>().front();
  const VoxelVolume fresh = makeToothPhantom(parsePhantomUrl("phantom:tooth?size=128,128,88"));
  const TissueMap& map = *vo.tissueMap();
  const int pulp = map.find("pulp");
  const double air = vo.airValue.get(), iso = vo.isoValue.get(), scale = 1.0 / (2.0 * (iso - air));
  auto phi = [&](double v) { return std::clamp((v - air) * scale, 0.0, 1.0); };
  std::vector<glm::dvec3> pulpVoxels, cut;
  for (auto it = fresh.grid().cbeginValueOn(); it; ++it) {
    const openvdb::Coord c = it.getCoord();
    const glm::dvec3 p(c.x(), c.y(), c.z());
    if (map.labelAt(c.x(), c.y(), c.z()) == pulp && *it < iso) pulpVoxels.push_back(p);
    if (phi(*it) > 0.5 && phi(vo.volume()->valueAt(c.x(), c.y(), c.z())) <= 0.5) cut.push_back(p);
  }
  ASSERT_FALSE(cut.empty());
  double nearest = 1e9;
  for (const glm::dvec3& a : cut)
    for (const glm::dvec3& b : pulpVoxels) nearest = std::min(nearest, glm::length(a - b));
  const double h = fresh.voxelSize().x;
  EXPECT_NEAR(wall, (nearest - 0.5) * h, 0.6 * h) << "brute force: " << nearest << " voxels centre to centre";
  // The deepest cut, recounted: the lowest voxel cut through, below the top
  // of the starting material in its own column (the cut is straight down).
  double deepest = 0.0;
  for (const glm::dvec3& a : cut) {
    int top = int(a.y);
    while (top + 1 < fresh.dims().y && phi(fresh.valueAt(int(a.x), top + 1, int(a.z))) > 0.5) ++top;
    deepest = std::max(deepest, (top - a.y + 0.5) * h);
  }
  EXPECT_NEAR(medium.summary.deepestCut, deepest, 0.6 * h);
  EXPECT_LT(millDown(0.0035, 3.0, 1e9).results[1].thinnestWall, 0.25e-3);
  const double far = millDown(0.0078, 1.0, 1e9).results[1].thinnestWall;
  EXPECT_TRUE(far < 0.0 || far > 1.5e-3) << far;
}

// The cut front (#2's and #3's): a burr in contact, milling, cuts at a front
// that advances towards the hand at the feed speed. A single frame without
// contact keeps the front where it was: #3's coupled tool lost all its
// contacts for one frame after a stamp in the §8.2 replay and stepped a
// penalty depth further in, and a front that jumped there cut 0.035 mm³ at
// once. Out of contact for a second frame the front is the burr again.
TEST(CutFront, OneFrameWithoutContactDoesNotMoveTheFront) {
  VoxelVolume volume = slab();
  VoxelScene scene;
  scene.addVolume(volume, glm::dmat4(1.0), kIso);
  const FeedLaw law{200.0, kTool.tipRadius};
  CutFront front;
  const glm::dvec3 burr(0.0, 0.4e-3, 0.0), hand(0.0, -0.5e-3, 0.0), deeper(0.0, 0.1e-3, 0.0);
  front.reset(burr);
  front.step(scene, law, burr, hand, true, true, 1.0, 1e-3);  // 1 N at hardness 1: 5 µm a frame
  const glm::dvec3 fed = front.centre();
  EXPECT_NEAR(fed.y, burr.y - 5e-6, 1e-9);
  front.step(scene, law, deeper, hand, false, true, 1.0, 1e-3);
  EXPECT_EQ(front.centre(), fed) << "one frame out of contact moved the front to the burr";
  front.step(scene, law, deeper, hand, false, true, 1.0, 1e-3);
  EXPECT_EQ(front.centre(), deeper) << "out of contact for two frames the front is the burr";
}
