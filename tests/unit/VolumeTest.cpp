// VoxelVolume, trilinear sampling, the tooth phantom, milling and the point shell.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <thread>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "millsim/volume/BlockChannel.h"
#include "millsim/volume/Milling.h"
#include "millsim/volume/PointShell.h"
#include "millsim/volume/ToothPhantom.h"
#include "millsim/volume/VoxelScene.h"
#include "millsim/volume/VolumeSampler.h"
#include "millsim/volume/VoxelVolume.h"

using namespace millsim;

namespace {

template <class F> VoxelVolume makeVolume(glm::ivec3 n, double h, float air, F&& f) {
  std::vector<float> v(std::size_t(n.x) * n.y * n.z);
  for (int k = 0; k < n.z; ++k)
    for (int j = 0; j < n.y; ++j)
      for (int i = 0; i < n.x; ++i) v[(std::size_t(k) * n.y + j) * n.x + i] = f(i, j, k);
  return VoxelVolume::fromDense(v.data(), n, glm::dvec3(h), air);
}

// Solid ball of radius R (voxels) with a one-voxel anti-aliased edge; 1 inside, 0 outside.
VoxelVolume ball(int n, double R) {
  const double c = (n - 1) * 0.5;
  return makeVolume({n, n, n}, 1e-3, 0.f, [&](int i, int j, int k) {
    const double r = std::sqrt((i - c) * (i - c) + (j - c) * (j - c) + (k - c) * (k - c));
    return float(std::clamp(0.5 + (R - r), 0.0, 1.0));
  });
}

}  // namespace

TEST(VoxelVolume, PlacementFollowsX3DVolumeData) {
  auto v = makeVolume({4, 3, 2}, 0.5e-3, -1.f, [](int, int, int) { return 1.f; });
  EXPECT_EQ(v.indexToLocal({0, 0, 0}), glm::dvec3(-0.75e-3, -0.5e-3, -0.25e-3));
  EXPECT_EQ(v.indexToLocal({3, 2, 1}), glm::dvec3(0.75e-3, 0.5e-3, 0.25e-3));
  const glm::dvec3 back = v.localToIndex(v.indexToLocal({1, 2, 1}));
  EXPECT_NEAR(glm::length(back - glm::dvec3(1, 2, 1)), 0.0, 1e-12);
}

TEST(VoxelVolume, AirIsSparseBackground) {
  // A small cube of material in a large air volume stores only the cube's leaves.
  auto v = makeVolume({128, 128, 128}, 1e-3, -1000.f, [](int i, int j, int k) {
    return (i >= 60 && i < 68 && j >= 60 && j < 68 && k >= 60 && k < 68) ? 500.f : -1000.f;
  });
  EXPECT_EQ(v.activeVoxels(), 512u);
  EXPECT_LT(v.memoryBytes(), 1024u * 1024u);  // a dense copy would be 8 MiB
  EXPECT_EQ(v.valueAt(0, 0, 0), -1000.f);
  EXPECT_EQ(v.valueAt(64, 64, 64), 500.f);
  // Below-air values are stored as air.
  auto w = makeVolume({8, 8, 8}, 1e-3, -1000.f, [](int, int, int) { return -1500.f; });
  EXPECT_EQ(w.valueAt(3, 3, 3), -1000.f);
}

TEST(VoxelVolume, BadShapesAreRefused) {
  float one = 1.f;
  EXPECT_THROW(VoxelVolume::fromDense(&one, {0, 1, 1}, glm::dvec3(1e-3), 0.f), VolumeError);
  EXPECT_THROW(VoxelVolume::fromDense(&one, {1, 1, 1}, glm::dvec3(0.0), 0.f), VolumeError);
  EXPECT_THROW(VoxelVolume::fromDense(&one, {1, 1, 1}, glm::dvec3(-1e-3), 0.f), VolumeError);
  EXPECT_THROW(VoxelVolume::fromDense(&one, {1, 1, 1}, glm::dvec3(std::nan("")), 0.f), VolumeError);
  EXPECT_THROW(VoxelVolume::fromDense(&one, {1, 1, 1}, glm::dvec3(0.1e-3, 0.9e-6, 0.1e-3), 0.f), VolumeError);
  EXPECT_THROW(VoxelVolume::fromDense(&one, {1, 1, 1}, glm::dvec3(0.1e-3, 0.1e-3, 0.011), 0.f), VolumeError);
  EXPECT_NO_THROW(VoxelVolume::fromDense(&one, {1, 1, 1}, glm::dvec3(kMinVoxelSize, 0.1e-3, kMaxVoxelSize), 0.f));
  try {
    checkVolumeShape("big.nrrd", {100000, 100000, 100000}, glm::dvec3(1e-3));
    FAIL();
  } catch (const VolumeError& e) {
    EXPECT_NE(std::string(e.what()).find("big.nrrd: dimensions 100000x100000x100000"), std::string::npos);
  }
}

TEST(VolumeSampler, TrilinearIsExactOnLinearFields) {
  auto v = makeVolume({16, 16, 16}, 1e-3, -1000.f, [](int i, int j, int k) { return 2.f * i - 3.f * j + 0.5f * k + 7.f; });
  VolumeSampler s(v);
  for (glm::dvec3 p : {glm::dvec3(3.25, 4.5, 5.75), glm::dvec3(1, 2, 3), glm::dvec3(10.9, 1.1, 7.3)}) {
    EXPECT_NEAR(s.density(p), 2 * p.x - 3 * p.y + 0.5 * p.z + 7, 1e-4) << p.x;
    const glm::dvec3 g = s.gradient(p);
    EXPECT_NEAR(g.x, 2.0, 1e-4);
    EXPECT_NEAR(g.y, -3.0, 1e-4);
    EXPECT_NEAR(g.z, 0.5, 1e-4);
  }
}

TEST(VolumeSampler, GradientPointsIntoABall) {
  auto v = ball(40, 12.0);
  VolumeSampler s(v);
  const glm::dvec3 c(19.5);
  for (const glm::dvec3 dir : {glm::dvec3(1, 0, 0), glm::normalize(glm::dvec3(1, 1, 0)),
                               glm::normalize(glm::dvec3(-1, 2, 3)), glm::normalize(glm::dvec3(0.3, -0.2, -1))}) {
    const glm::dvec3 p = c + dir * 12.0;  // on the surface
    EXPECT_NEAR(s.density(p), 0.5, 0.08);
    const glm::dvec3 g = glm::normalize(s.gradient(p));
    EXPECT_GT(glm::dot(g, -dir), 0.98);  // density grows inwards
  }
  EXPECT_EQ(s.density({-50, 0, 0}), 0.f);  // outside the volume: air
}

// A point far outside the index range, or NaN, reads air: no undefined cast
// to int (UBSan flags it) and no NaN weight (a NaN point gave a NaN density).
TEST(VolumeSampler, ReadsAirFarOutsideAndAtNaN) {
  auto v = ball(40, 12.0);
  VolumeSampler s(v);
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  for (const glm::dvec3 p : {glm::dvec3(1e300, 19.5, 19.5), glm::dvec3(19.5, -1e300, 19.5), glm::dvec3(19.5, 19.5, 3e9),
                             glm::dvec3(nan, 19.5, 19.5), glm::dvec3(19.5, nan, nan), glm::dvec3(-inf, 19.5, 19.5)}) {
    EXPECT_EQ(s.density(p), 0.f) << p.x << " " << p.y << " " << p.z;
    const glm::dvec3 g = s.gradient(p);
    EXPECT_TRUE(std::isfinite(g.x) && std::isfinite(g.y) && std::isfinite(g.z)) << p.x << " " << p.y << " " << p.z;
  }
  EXPECT_EQ(s.density({19.5, 19.5, 19.5}), 1.f);  // and the ball is still there
}

// The sampler keeps the buffers of the leaves it read last and the air tiles
// (VolumeSampler.h): after milling has changed voxels in place and turned
// dense tiles into leaves, it reads exactly what a new sampler reads. (Kept
// dense tiles read stale values here.)
TEST(VolumeSampler, ReadsWhatMillingWroteAfterCachingTheLeaves) {
  const int n = 40;
  // Material below y = 20 (dense 8³ blocks there are tiles), air above.
  auto v = makeVolume({n, n, n}, 1e-3, 0.f, [](int, int j, int) { return j < 20 ? 1.f : 0.f; });
  v.grid().tree().prune();  // uniform blocks become tiles, as a loaded CT's do
  ASSERT_LT(v.grid().tree().leafCount(), 5u * 5u * 3u) << "the material's inner blocks are tiles";
  VolumeSampler kept(v);
  std::vector<glm::dvec3> points;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(8.0, 31.0);
  for (int i = 0; i < 400; ++i) points.push_back({u(rng), u(rng), u(rng)});
  const glm::dvec3 centres[] = {glm::dvec3(20, 19, 20), glm::dvec3(12.3, 14.4, 26.2), glm::dvec3(26.6, 10.2, 13.4)};
  // Last, the cells around each stamp: their leaves (and tiles) are the ones the sampler holds when milling starts.
  for (const glm::dvec3& c : centres)
    for (double d : {-1.6, -0.4, 0.7, 1.9}) points.push_back(c + glm::dvec3(d, 0.3 * d, -0.2 * d));
  for (const glm::dvec3& p : points) (void)kept.density(p);
  Miller miller(v, 0.5f);
  DirtyBlocks dirty(v.dims());
  for (const glm::dvec3& c : centres) ASSERT_GT(miller.stamp(v.indexToLocal(c), 5e-3, dirty).voxelsChanged, 0);
  std::reverse(points.begin(), points.end());  // the stamps' cells first, before anything else evicts them
  VolumeSampler fresh(v);
  int changed = 0;
  for (const glm::dvec3& p : points) {
    EXPECT_EQ(kept.density(p), fresh.density(p)) << p.x << " " << p.y << " " << p.z;
    changed += fresh.density(p) < 1.f && p.y < 18.0;
  }
  EXPECT_GT(changed, 20) << "the stamps reached many of the points";
}

// A round stamp leaves out the voxels nearer the last round stamp's centre
// than its own (Miller::lastRound_): exactly what a Miller that remembers
// nothing does, stamp by stamp — the same removed volume, changed voxels,
// dirty blocks and box, and at the end the same grid — while the burr creeps,
// holds still, jumps, changes size, and cuts voxels denser than a first stamp
// leaves. It also leaves out the last stamp's core (all air by then).
TEST(Miller, SkippingWhatTheLastStampSettledChangesNothing) {
  const glm::ivec3 n(40, 36, 44);
  const float air = -1000.f, iso = 700.f;
  std::vector<float> values(std::size_t(n.x) * n.y * n.z);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> noise(-300.f, 300.f);
  for (int k = 0; k < n.z; ++k)
    for (int j = 0; j < n.y; ++j)
      for (int i = 0; i < n.x; ++i)  // a slab below y = 20, denser (to 3000) with depth, noisy
        values[(std::size_t(k) * n.y + j) * n.x + i] =
            j < 20 ? std::min(3000.f, 1200.f + 100.f * float(20 - j) + noise(rng)) : air;
  const glm::dvec3 h(1e-4, 0.8e-4, 1.2e-4);  // not cubic: the skip's test weighs each axis
  VoxelVolume remembering = VoxelVolume::fromDense(values.data(), n, h, air);
  VoxelVolume forgetting = VoxelVolume::fromDense(values.data(), n, h, air);
  Miller miller(remembering, iso);
  std::uniform_real_distribution<double> step(-0.25, 0.25), jump(10.0, 30.0);
  glm::dvec3 c(20.0, 21.0, 22.0);  // index space
  double radius = 5e-4;
  int changedStamps = 0;
  for (int s = 0; s < 400; ++s) {
    if (s % 100 == 60) c = glm::dvec3(jump(rng), jump(rng) - 8.0, jump(rng));  // elsewhere
    else if (s % 25 == 7) {}  // held still: the same centre again
    else c += glm::dvec3(step(rng), step(rng) - 0.08, step(rng));  // creeping, mostly down
    if (s == 200) radius = 3.5e-4;
    if (s == 300) radius = 5e-4;
    DirtyBlocks a(n), b(n);
    const StampResult ra = miller.stamp(remembering.indexToLocal(c), radius, a);
    Miller fresh(forgetting, iso);
    const StampResult rb = fresh.stamp(forgetting.indexToLocal(c), radius, b);
    ASSERT_EQ(ra.removedVolume, rb.removedVolume) << "stamp " << s;
    ASSERT_EQ(ra.voxelsChanged, rb.voxelsChanged) << "stamp " << s;
    ASSERT_EQ(a.origins(), b.origins()) << "stamp " << s;
    ASSERT_EQ(a.voxelLo(), b.voxelLo()) << "stamp " << s;
    ASSERT_EQ(a.voxelHi(), b.voxelHi()) << "stamp " << s;
    changedStamps += ra.voxelsChanged > 0;
  }
  EXPECT_GT(changedStamps, 200) << "the burr cut in most stamps";
  int differ = 0;
  for (int k = 0; k < n.z; ++k)
    for (int j = 0; j < n.y; ++j)
      for (int i = 0; i < n.x; ++i) {
        const openvdb::Coord at(i, j, k);
        differ += remembering.grid().tree().getValue(at) != forgetting.grid().tree().getValue(at);
      }
  EXPECT_EQ(differ, 0);
}

// The sampler's window (a dense copy around focus()) reads exactly what the
// grid holds: inside it, across its faces and outside it; after milling once
// told of it (refresh(), as VoxelScene::mill does); and after moving on.
TEST(VolumeSampler, WindowReadsWhatTheGridHolds) {
  const int n = 48;
  auto v = makeVolume({n, n, n}, 1e-3, 0.f, [](int i, int j, int k) {
    return j < 24 ? 1.f : float(std::clamp(0.5 + 0.1 * (i - 20) - 0.05 * (k - 30), 0.0, 1.0));
  });
  v.grid().tree().prune();  // tiles as well as leaves
  VolumeSampler windowed(v);
  windowed.enableWindow(16);
  std::mt19937 rng(3);
  auto compare = [&](const glm::dvec3& centre, const char* when) {
    VolumeSampler fresh(v);
    std::uniform_real_distribution<double> u(-11.0, 11.0);  // the window spans ±8
    int differ = 0;
    for (int i = 0; i < 3000; ++i) {
      const glm::dvec3 p = centre + glm::dvec3(u(rng), u(rng), u(rng));
      differ += windowed.density(p) != fresh.density(p);
    }
    EXPECT_EQ(differ, 0) << when;
  };
  const glm::dvec3 a(20.3, 23.6, 21.2), b(31.7, 18.2, 27.9);
  windowed.focus(a, 5.0);
  compare(a, "after focusing");
  Miller miller(v, 0.5f);
  DirtyBlocks dirty(v.dims());
  ASSERT_GT(miller.stamp(v.indexToLocal(a + glm::dvec3(1.5, -2.0, 0.5)), 4e-3, dirty).voxelsChanged, 0);
  windowed.refresh(dirty.voxelLo(), dirty.voxelHi());
  compare(a, "after milling");
  windowed.focus(b, 5.0);
  compare(b, "after moving on");
  windowed.focus(b + glm::dvec3(1.0), 5.0);  // still held: no copy, same values
  compare(b, "after a small move");
  windowed.focus(a, 20.0);  // a reach the window cannot hold: left where it was
  compare(b, "after a reach too large");
}

// VoxelScene keeps its sampler's window current with its own milling: after
// each stamp near the focus, field() equals a fresh sampler's density.
TEST(VoxelScene, FieldFollowsMillingInTheFocusWindow) {
  auto v = ball(48, 18.0);
  VoxelScene scene;
  scene.addVolume(v, glm::dmat4(1.0), 0.5);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const glm::dvec3 surface = v.indexToLocal(glm::dvec3(23.5 + 18.0, 23.5, 23.5));  // on the ball, +x
  int differ = 0;
  for (int stamp = 0; stamp < 30; ++stamp) {
    const glm::dvec3 c = surface + 1e-3 * glm::dvec3(-0.2 * stamp + u(rng), u(rng), u(rng));
    scene.focus(c, 5e-3);
    scene.mill(c, 3e-3);
    VolumeSampler fresh(v);
    for (int i = 0; i < 200; ++i) {
      const glm::dvec3 p = c + 6e-3 * glm::dvec3(u(rng), u(rng), u(rng));
      differ += scene.field(p) != double(fresh.density(v.localToIndex(p))) - 0.5;
    }
  }
  EXPECT_EQ(differ, 0);
}

// A volume scaled and moved (not turned), as every shipped lesson's, is
// sampled through the diagonal of its world-to-index map: the same values as
// through the whole matrix; a turned one goes through the matrix.
TEST(VoxelScene, AScaledAndMovedVolumeSamplesAsThroughTheWholeMap) {
  auto v = ball(32, 12.0);
  VoxelScene scene;
  scene.addVolume(v, glm::scale(glm::translate(glm::dmat4(1.0), glm::dvec3(0.01, -0.02, 0.003)), glm::dvec3(1.5, 0.8, 2.0)),
                  0.5);
  const glm::dmat4 turn = glm::rotate(glm::dmat4(1.0), 0.3, glm::dvec3(0, 1, 0));
  scene.addVolume(v, turn, 0.5);
  const auto& moved = scene.volume(0);
  ASSERT_TRUE(moved.axisAligned);
  EXPECT_FALSE(scene.volume(1).axisAligned);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-0.05, 0.05);
  int differ = 0;
  for (int i = 0; i < 2000; ++i) {
    const glm::dvec3 p(u(rng), u(rng), u(rng));
    differ += moved.toIndex(p) != moved.worldToIndexLinear * p + moved.worldToIndexOffset;
  }
  EXPECT_EQ(differ, 0);
}

TEST(ToothPhantom, IsDeterministic) {
  const ToothPhantomOptions small{{64, 64, 44}, 0.4e-3, false};
  EXPECT_EQ(makeToothPhantom(small).contentHash(), makeToothPhantom(small).contentHash());
  EXPECT_NE(makeToothPhantom(small).contentHash(), makeToothPhantom({{64, 64, 44}, 0.4e-3, true}).contentHash());
}

// The phantom is built sparse, a leaf at a time, skipping blocks the tooth
// cannot reach (issue 44: at 25 µm the dense box was 3 GB): it must equal
// every voxel computed alone, densities and labels, with and without the
// socket, at two resolutions (the block test's margin scales with h). Built
// together in one pass (a scene with both urls), each is the same grid.
TEST(ToothPhantom, TheSparseBuildHasEveryVoxelsOwnValue) {
  for (const char* url : {"phantom:tooth?size=96,96,66", "phantom:tooth?size=128,128,88&socket=1",
                          "phantom:tooth?size=200,180,120&voxel=0.00008"}) {
    SCOPED_TRACE(url);
    const ToothPhantomOptions o = parsePhantomUrl(url);
    const VoxelVolume density = makeToothPhantom(o), labels = makeToothPhantomLabels(o);
    auto d = density.grid().getConstAccessor();
    auto l = labels.grid().getConstAccessor();
    std::uint64_t material = 0, labelled = 0, wrong = 0;
    for (int k = 0; k < o.dims.z; ++k)
      for (int j = 0; j < o.dims.y; ++j)
        for (int i = 0; i < o.dims.x; ++i) {
          const openvdb::Coord c(i, j, k);
          const float v = toothPhantomVoxel(o, {i, j, k});
          const int label = toothPhantomLabelVoxel(o, {i, j, k});
          material += v > ToothDensities::air, labelled += label > 0;
          const float got = d.isValueOn(c) ? d.getValue(c) : ToothDensities::air;
          const int gotLabel = l.isValueOn(c) ? int(l.getValue(c)) : 0;
          wrong += (v > ToothDensities::air ? got != v : got != ToothDensities::air) || gotLabel != label;
        }
    EXPECT_EQ(wrong, 0u);
    EXPECT_EQ(density.activeVoxels(), material);
    EXPECT_EQ(labels.activeVoxels(), labelled);
    EXPECT_GT(material, 10000u);
    const ToothPhantomWithLabels both = makeToothPhantomWithLabels(o);
    EXPECT_EQ(both.densities.contentHash(), density.contentHash());
    EXPECT_EQ(both.labels.contentHash(), labels.contentHash());
    EXPECT_EQ(both.labels.activeVoxels(), labelled);
  }
}

TEST(ToothPhantom, AnatomyHasEnamelOverDentinOverPulp) {
  using D = ToothDensities;
  // Sample the phantom's density function at points in the tooth frame (metres).
  const float cusp = toothPhantomDensity({2.3e-3, 9.0e-3, 2.0e-3}, false);  // 0.6 mm under a cusp tip
  const float dentin = toothPhantomDensity({0.0, 6.0e-3, 2.0e-3}, false);
  const float pulp = toothPhantomDensity({0.0, 3.6e-3, 0.0}, false);
  const float canal = toothPhantomDensity({-2.4e-3, -3.0e-3, 0.1e-3}, false);
  const float root = toothPhantomDensity({-2.4e-3, -3.0e-3, 1.2e-3}, false);
  const float air = toothPhantomDensity({0.0, 12.0e-3, 0.0}, false);
  const float between = toothPhantomDensity({0.0, -8.0e-3, 0.0}, false);  // between the roots
  EXPECT_EQ(cusp, D::enamel);
  EXPECT_EQ(dentin, D::dentin);
  EXPECT_EQ(pulp, D::softTissue);
  EXPECT_EQ(canal, D::softTissue);
  EXPECT_EQ(root, D::dentin);
  EXPECT_EQ(air, D::air);
  EXPECT_EQ(between, D::air);
  EXPECT_GT(cusp, dentin);
  EXPECT_GT(dentin, pulp);
  // The socket surrounds the roots with bone and a ligament gap.
  EXPECT_EQ(toothPhantomDensity({0.0, -8.0e-3, 0.0}, true), D::bone);
  EXPECT_EQ(toothPhantomDensity({0.0, -8.0e-3, 5.0e-3}, true), D::bone);
}

TEST(ToothPhantom, UrlOptions) {
  auto o = parsePhantomUrl("phantom:tooth?size=128,128,88&socket=1");
  EXPECT_EQ(o.dims, glm::ivec3(128, 128, 88));
  EXPECT_DOUBLE_EQ(o.voxelSize, 0.2e-3);  // same physical extent as the default
  EXPECT_TRUE(o.socket);
  EXPECT_DOUBLE_EQ(parsePhantomUrl("phantom:tooth?voxel=0.00005").voxelSize, 0.05e-3);
  EXPECT_THROW(parsePhantomUrl("phantom:tooth?size=1,2"), VolumeError);
  EXPECT_THROW(parsePhantomUrl("phantom:tooth?colour=red"), VolumeError);
  EXPECT_THROW(parsePhantomUrl("phantom:tooth?voxel=-1"), VolumeError);
  EXPECT_THROW(parsePhantomUrl("phantom:knee"), VolumeError);
}

TEST(Milling, OneStampRemovesTheSphereCapVolume) {
  // A half-space of material (y below the middle), iso midway between air and material.
  const int n = 64;
  const double h = 0.1e-3;
  auto v = makeVolume({n, n, n}, h, 0.f, [&](int, int j, int) { return float(std::clamp(32.0 - j, 0.0, 1.0)); });
  // The surface (value 0.5) lies at index y = 31.5, i.e. local y = 0.
  for (double depthVoxels : {2.0, 3.5, 5.0}) {
    auto w = makeVolume({n, n, n}, h, 0.f, [&](int, int j, int) { return float(std::clamp(32.0 - j, 0.0, 1.0)); });
    Miller miller(w, 0.5f);
    DirtyBlocks dirty(w.dims());
    const double r = 8 * h, d = depthVoxels * h;
    const StampResult res = miller.stamp({0.0, r - d, 0.0}, r, dirty);
    const double cap = std::numbers::pi * d * d * (3 * r - d) / 3.0;
    EXPECT_NEAR(res.removedVolume / cap, 1.0, 0.02) << "depth " << depthVoxels << " voxels";
    EXPECT_GT(res.voxelsChanged, 0);
    EXPECT_FALSE(dirty.empty());
    // Every dirty block really contains a changed voxel's block, and the stamp is local.
    EXPECT_LE(dirty.origins().size(), 27u);
  }
  (void)v;
}

TEST(Milling, StampsNeverAddMaterialAndIgnoreBadInput) {
  auto v = ball(32, 8.0);
  Miller miller(v, 0.5f);
  DirtyBlocks dirty(v.dims());
  EXPECT_EQ(miller.stamp({std::nan(""), 0, 0}, 1e-3, dirty).voxelsChanged, 0);
  EXPECT_EQ(miller.stamp({0, 0, 0}, -1.0, dirty).voxelsChanged, 0);
  EXPECT_EQ(miller.stamp({1.0, 1.0, 1.0}, 1e-3, dirty).voxelsChanged, 0);  // far outside
  const float before = v.valueAt(15, 15, 15);
  auto r1 = miller.stamp({0, 0, 0}, 3e-3, dirty);
  EXPECT_GT(r1.removedVolume, 0.0);
  EXPECT_LT(v.valueAt(15, 15, 15), before);
  auto r2 = miller.stamp({0, 0, 0}, 3e-3, dirty);  // same place again: nothing left there
  EXPECT_EQ(r2.voxelsChanged, 0);
  EXPECT_NEAR(miller.totalRemoved(), r1.removedVolume, 1e-15);
}

TEST(PointShell, SurfaceVoxelsOfABallWithOutwardNormals) {
  auto v = ball(48, 15.0);
  PointShell shell(v, 0.5f, 1);
  ASSERT_GT(shell.size(), 0u);
  // Roughly the sphere's surface area in voxels (4πR² ≈ 2827), within discretisation.
  EXPECT_GT(shell.size(), 2000u);
  EXPECT_LT(shell.size(), 4500u);
  double minDot = 1.0;
  shell.forEach([&](const ShellPoint& p) {
    const glm::vec3 radial = glm::normalize(p.position);
    minDot = std::min(minDot, double(glm::dot(radial, p.normal)));
    EXPECT_NEAR(glm::length(p.position) / 1e-3, 15.0, 1.0);
  });
  EXPECT_GT(minDot, 0.8);
}

// Points sit on the iso-surface, not at voxel centres up to a voxel inside it
// (contact would start that late): on the ball's linear edge the iso-surface
// is the sphere r = R exactly.
TEST(PointShell, PointsLieOnTheIsoSurface) {
  auto v = ball(48, 15.0);
  for (int scale : {1, 2, 3}) {
    PointShell shell(v, 0.5f, scale);
    // An empty shell would leave `worst` at 0 and pass.
    ASSERT_GT(shell.size(), 0u) << "scale " << scale << ": the ball's shell is empty";
    double worst = 0.0;
    std::size_t visited = 0;
    shell.forEach([&](const ShellPoint& p) {
      ++visited;
      worst = std::max(worst, std::abs(glm::length(p.position) / 1e-3 - 15.0));
    });
    EXPECT_EQ(visited, shell.size()) << "scale " << scale << ": forEach skipped points";
    // Scale 1: linear interpolation along the normal (voxel centres were up to 1 voxel off);
    // coarser scales start from the block's material.
    EXPECT_LT(worst, scale == 1 ? 0.2 : 0.5) << "scale " << scale << ": voxels off the sphere";
  }
}

// A plate one voxel thick has a surface on each side: each face gets points
// with its own outward normal, at every scale and alignment to the blocks.
// (At scale 2 one alignment used to give a single layer facing down from the
// top, and the tool fell onto the far face.)
TEST(PointShell, AVoxelThinPlateHasPointsOnBothFaces) {
  for (int row : {16, 17, 18})
    for (int scale : {1, 2, 3}) {
      auto v = makeVolume({32, 36, 32}, 1e-3, 0.f, [&](int, int j, int) { return j == row ? 1.f : 0.f; });
      PointShell shell(v, 0.5f, scale);
      const double centre = v.indexToLocal(glm::dvec3(0, row, 0)).y;
      int up = 0, down = 0, wrong = 0;
      shell.forEach([&](const ShellPoint& p) {
        const double y = (double(p.position.y) - centre) / 1e-3;  // voxels above the plate's centre
        if (p.normal.y > 0.9f) up += 1, wrong += y < 0.0;
        else if (p.normal.y < -0.9f) down += 1, wrong += y > 0.0;
      });
      EXPECT_GT(up, 0) << "row " << row << ", scale " << scale << ": no point faces up";
      EXPECT_GT(down, 0) << "row " << row << ", scale " << scale << ": no point faces down";
      EXPECT_EQ(wrong, 0) << "row " << row << ", scale " << scale << ": points face away from their side";
    }
}

TEST(PointShell, CoarserScalesHaveFewerPoints) {
  auto v = ball(64, 24.0);
  const std::size_t n1 = PointShell(v, 0.5f, 1).size(), n2 = PointShell(v, 0.5f, 2).size(),
                    n3 = PointShell(v, 0.5f, 3).size();
  EXPECT_GT(n1, 3 * n2);  // about 1/s² as many
  EXPECT_GT(n2, n3);
  EXPECT_THROW(PointShell(v, 0.5f, 0), VolumeError);
}

TEST(PointShell, BoxQueriesVisitOnlyOverlappingBuckets) {
  auto v = ball(64, 24.0);
  PointShell shell(v, 0.5f, 1);
  Aabb box;
  box.lo = glm::vec3(20e-3, -3e-3, -3e-3);
  box.hi = glm::vec3(26e-3, 3e-3, 3e-3);
  std::size_t inBox = 0, visited = 0;
  shell.forEachCandidate([&](const Aabb& b) { return b.overlaps(box); },
                         [&](const ShellPoint& p) {
                           ++visited;
                           inBox += p.position.x >= box.lo.x && p.position.x <= box.hi.x &&
                                    std::abs(p.position.y) <= 3e-3 && std::abs(p.position.z) <= 3e-3;
                         });
  std::size_t brute = 0;
  shell.forEach([&](const ShellPoint& p) {
    brute += p.position.x >= box.lo.x && p.position.x <= box.hi.x && std::abs(p.position.y) <= 3e-3 &&
             std::abs(p.position.z) <= 3e-3;
  });
  EXPECT_EQ(inBox, brute);  // no point in the box is missed
  EXPECT_GT(brute, 0u);
  EXPECT_LT(visited, shell.size() / 5);  // and most of the shell is never visited
}

TEST(PointShell, IncrementalUpdateEqualsRebuild) {
  // Both paths: by changed blocks, and the fast one by the changed voxels' box.
  for (int scale : {1, 2, 3, 4, 5, 6, -1, -2, -3, -6}) {
    const bool fast = scale < 0;
    scale = std::abs(scale);
    auto v = ball(64, 22.0);
    PointShell shell(v, 0.5f, scale);
    Miller miller(v, 0.5f);
    DirtyBlocks dirty(v.dims());
    // A few stamps on the surface, one crossing block borders, one drilling inwards.
    for (glm::dvec3 c : {glm::dvec3(22e-3, 0, 0), glm::dvec3(0, 21.5e-3, 0.5e-3), glm::dvec3(16e-3, 0, 0),
                         glm::dvec3(-8e-3, -8e-3, 19e-3)}) {
      miller.stamp(c, 5e-3, dirty);
      if (fast) shell.update(v, dirty);
      else shell.update(v, dirty.origins());
      dirty.clear();
    }
    PointShell fresh(v, 0.5f, scale);
    const auto a = shell.points(), b = fresh.points();
    ASSERT_EQ(a.size(), b.size()) << "scale " << scale;
    for (std::size_t i = 0; i < a.size(); ++i) {
      ASSERT_EQ(a[i].position, b[i].position) << "scale " << scale << " point " << i;
      ASSERT_EQ(a[i].normal, b[i].normal) << "scale " << scale << " point " << i;
    }
  }
}

// The shells a VoxelScene keeps follow random milling exactly: after every
// few stamps, each shell (in use every frame, looked at now and then, or
// dormant until the end) holds bit for bit the points and normals a rebuild
// from the milled voxels gives.
TEST(PointShell, IncrementalUpdateEqualsRebuildAfterRandomMilling) {
  auto v = ball(64, 24.0);
  VoxelScene scene;
  scene.addVolume(v, glm::dmat4(1.0), 0.5);
  const int scales[] = {1, 2, 3, 6};
  for (int s : scales) scene.pointShell(0, s);
  std::mt19937 rng(15);
  std::uniform_real_distribution<double> u(-1.0, 1.0), radius(1.0e-3, 6.0e-3);
  auto compare = [&](int s, int stamp) {
    const auto a = scene.shell(0, s).points(), b = PointShell(v, 0.5f, s).points();
    ASSERT_EQ(a.size(), b.size()) << "scale " << s << " after stamp " << stamp;
    for (std::size_t i = 0; i < a.size(); ++i) {
      ASSERT_EQ(a[i].position, b[i].position) << "scale " << s << " stamp " << stamp << " point " << i;
      ASSERT_EQ(a[i].normal, b[i].normal) << "scale " << s << " stamp " << stamp << " point " << i;
    }
  };
  double removed = 0.0;
  for (int stamp = 0; stamp < 120; ++stamp) {
    // Near the ball's surface (radius 24 voxels of 1 mm), sometimes deeper, a burr path in places.
    glm::dvec3 c(u(rng), u(rng), u(rng));
    c = glm::normalize(c) * (20e-3 + 6e-3 * u(rng));
    removed += scene.mill(c, radius(rng));
    scene.pointShell(0, 1);                         // in use: follows every stamp
    if (stamp % 7 == 0) scene.pointShell(0, 2);     // looked at now and then
    if (stamp % 30 == 29) {
      ASSERT_NO_FATAL_FAILURE(compare(3, stamp));
    }
  }
  EXPECT_GT(removed, 0.0);
  for (int s : scales) ASSERT_NO_FATAL_FAILURE(compare(s, 120));  // scale 6 was dormant throughout
  for (int s : scales) EXPECT_EQ(scene.shell(0, s).droppedPoints(), 0u) << "scale " << s;
}

// Issue 44: a shell is built on TBB's threads, bucket by bucket from dense
// copies; rebuildAll still reads voxel by voxel through an accessor. Both must
// give the same points, in the same order, at every scale (the phantom's
// enamel, pulp and roots; a ball milled at random, whose cuts leave slivers).
TEST(PointShell, TheParallelBuildEqualsTheVoxelByVoxelOne) {
  auto compare = [](const VoxelVolume& v, float iso, int s, const char* what) {
    PointShell rebuilt(v, iso, s);
    const auto a = PointShell(v, iso, s).points();
    rebuilt.rebuildAll(v);
    const auto b = rebuilt.points();
    ASSERT_GT(a.size(), 100u) << what << " scale " << s;
    ASSERT_EQ(a.size(), b.size()) << what << " scale " << s;
    for (std::size_t i = 0; i < a.size(); ++i) {
      ASSERT_EQ(a[i].position, b[i].position) << what << " scale " << s << " point " << i;
      ASSERT_EQ(a[i].normal, b[i].normal) << what << " scale " << s << " point " << i;
    }
  };
  const VoxelVolume tooth = makeToothPhantom(ToothPhantomOptions{});
  for (int s : {1, 2, 3, 5}) ASSERT_NO_FATAL_FAILURE(compare(tooth, 700.f, s, "phantom"));
  auto v = ball(64, 24.0);
  Miller miller(v, 0.5f);
  DirtyBlocks dirty(v.dims());
  std::mt19937 rng(44);
  std::uniform_real_distribution<double> u(-1.0, 1.0), radius(1.0e-3, 6.0e-3);
  for (int stamp = 0; stamp < 60; ++stamp) {
    const glm::dvec3 c = glm::normalize(glm::dvec3(u(rng), u(rng), u(rng))) * (20e-3 + 6e-3 * u(rng));
    miller.stamp(c, radius(rng), dirty);
  }
  for (int s : {1, 2, 3, 6}) ASSERT_NO_FATAL_FAILURE(compare(v, 0.5f, s, "milled ball"));
}

// Issue 15, part 4: the point shell of the tooth phantom at scale 1 costs at
// most 200 bytes per point, headroom for milling and scratch included, by
// the shell's own accounting (every buffer it holds is written when it is
// made, so that is its resident memory; the old layout, 512 points reserved
// per bucket, cost about 600). And the headroom covers what milling adds:
// the 2.5 mm hole MillingBench drills (the §8.2 procedure's) adds points,
// none is dropped, and the shell still equals a rebuild.
TEST(PointShell, PhantomShellCostsAtMost200BytesPerPointAndItsHeadroomCoversAHole) {
  VoxelVolume v = makeToothPhantom(ToothPhantomOptions{});
  PointShell shell(v, 700.f, 1);
  const std::size_t built = shell.size();
  ASSERT_GT(built, 40000u);
  const double perPoint = double(shell.memoryBytes()) / double(built);
  EXPECT_LE(perPoint, 200.0) << built << " points, " << shell.memoryBytes() << " bytes";
  const std::size_t headroom = shell.headroom();
  EXPECT_GE(headroom, 2 * built) << "headroom for milling: two slots per point";
  Miller miller(v, 700.f);
  DirtyBlocks dirty(v.dims());
  for (long f = 0; f < 4000; ++f) {
    // One turn per 400 frames, 0.4 mm off the axis, sinking 2.5 mm: the burr (0.6 mm) drills the fossa.
    const double a = 2.0 * std::numbers::pi * double(f % 400) / 400.0;
    miller.stamp({0.4e-3 * std::cos(a), 9.9e-3 - 2.5e-3 * double(f) / 4000.0, 0.4e-3 * std::sin(a)}, 0.6e-3, dirty);
    shell.update(v, dirty);
    dirty.clear();
  }
  const std::size_t added = shell.size() - built;
  EXPECT_GT(added, 500u) << "the hole must add surface, or this tests nothing";
  EXPECT_LT(added, headroom / 10) << "a hole uses a small part of the headroom";
  EXPECT_EQ(shell.droppedPoints(), 0u);
  EXPECT_GT(shell.relocations(), 0u) << "growing buckets moved into the headroom";
  const auto a = shell.points(), b = PointShell(v, 700.f, 1).points();
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].position, b[i].position) << "point " << i;
    ASSERT_EQ(a[i].normal, b[i].normal) << "point " << i;
  }
}

// Milling that outgrows a small headroom: the array is compacted in place and
// the shell still equals a rebuild; past that, a bucket keeps what fits and
// the dropped points are counted (the documented cap), never an allocation.
TEST(PointShell, OutgrownHeadroomCompactsThenDropsAndCounts) {
  auto v = ball(64, 24.0);
  PointShell shell(v, 0.5f, 1, 0, 2 * PointShell::kMaxBucketPoints);
  Miller miller(v, 0.5f);
  DirtyBlocks dirty(v.dims());
  bool compared = false;
  for (int i = 0; i < 200 && shell.droppedPoints() == 0; ++i) {
    // Holes drilled in along each axis, both ways: each adds its wall.
    const int axis = i % 3;
    const double sign = (i / 3) % 2 ? -1.0 : 1.0, depth = (24.0 - 1.0 * double(i / 6)) * 1e-3;
    glm::dvec3 c(0.0);
    c[axis] = sign * depth;
    miller.stamp(c, 3e-3, dirty);
    shell.update(v, dirty);
    dirty.clear();
    if (shell.compactions() > 0 && shell.droppedPoints() == 0 && !compared) {
      const auto a = shell.points(), b = PointShell(v, 0.5f, 1).points();
      ASSERT_EQ(a.size(), b.size()) << "after compaction, stamp " << i;
      for (std::size_t k = 0; k < a.size(); ++k) {
        ASSERT_EQ(a[k].position, b[k].position) << "point " << k;
        ASSERT_EQ(a[k].normal, b[k].normal) << "point " << k;
      }
      compared = true;
    }
  }
  EXPECT_TRUE(compared) << "milling never compacted the shell";
  EXPECT_GT(shell.droppedPoints(), 0u) << "milling never outgrew the headroom";
  EXPECT_LE(shell.size(), shell.capacity());
  EXPECT_EQ(shell.size(), shell.points().size());
}

TEST(PointShell, ToothPhantomCountsFallWithScale) {
  auto v = makeToothPhantom({{128, 128, 88}, 0.2e-3, false});
  const std::size_t n1 = PointShell(v, 700.f, 1).size(), n2 = PointShell(v, 700.f, 2).size(),
                    n3 = PointShell(v, 700.f, 3).size();
  EXPECT_GT(n1, n2);
  EXPECT_GT(n2, n3);
  EXPECT_GT(n3, 100u);
}

TEST(BlockChannel, GraphicsReplicaFollowsMillingOnAnotherThread) {
  auto v = ball(64, 24.0);
  VolumeReplica replica(v);
  BlockChannel channel(16);  // small, so the publisher must hold blocks back and retry
  std::atomic<bool> done{false};
  std::size_t applied = 0;
  // The graphics side: drains and reads its replica while milling goes on.
  std::thread graphics([&] {
    VolumeSampler reader(replica.volume());
    // The ball's centre (index 32: R = 24 voxels) is never milled (the groove
    // runs 20–26 voxels out): every read there, while blocks are being applied
    // around it, must see the material, exactly 1.
    std::size_t reads = 0, wrong = 0;
    float wrongValue = 1.f;
    while (!done.load(std::memory_order_acquire)) {
      applied += replica.apply(channel).size();
      const float d = reader.density({32, 32, 32});
      ++reads;
      if (d != 1.f) ++wrong, wrongValue = d;
    }
    applied += replica.apply(channel).size();
    EXPECT_GT(reads, 0u);
    EXPECT_EQ(wrong, 0u) << "of " << reads << " reads of the untouched centre, e.g. " << wrongValue;
  });
  // The haptic side: mills a groove around the ball, publishing after every stamp.
  Miller miller(v, 0.5f);
  DirtyBlocks dirty(v.dims());
  BlockPublisher publisher(v, channel);
  for (int s = 0; s < 200; ++s) {
    const double a = s * 0.03;
    miller.stamp({23e-3 * std::cos(a), 23e-3 * std::sin(a), 0.0}, 3e-3, dirty);
    publisher.publish(dirty.origins());
    dirty.clear();
  }
  while (publisher.publish({}) > 0) std::this_thread::yield();  // flush what did not fit
  done.store(true, std::memory_order_release);
  graphics.join();
  EXPECT_GT(applied, 0u);
  EXPECT_EQ(replica.volume().contentHash(), v.contentHash());
}

// HapticScene::mayHaveMaterialNear is a cull: wherever it says no, nothing
// sampled within the radius is material; and it does say no far from the
// tooth. Each point is probed at the largest radius it still says no for,
// where a bound too loose would show first. A rotated, scaled placement
// checks its metres-to-voxels bound.
TEST(MaterialBlocks, SaysNoOnlyWhereNothingWithinTheRadiusIsMaterial) {
  VoxelVolume tooth = makeToothPhantom({{64, 64, 44}, 0.4e-3, false});
  VoxelScene scene;
  const glm::dmat4 place = glm::scale(glm::rotate(glm::dmat4(1.0), 0.7, glm::normalize(glm::dvec3(1, 2, 3))),
                                      glm::dvec3(0.8));
  scene.addVolume(tooth, place, 700.0);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> box(-0.025, 0.025), unit(-1.0, 1.0);
  int no = 0;
  for (int i = 0; i < 300; ++i) {
    const glm::dvec3 p(box(rng), box(rng), box(rng));
    if (scene.mayHaveMaterialNear(p, 0.0)) continue;
    ++no;
    double lo = 0.0, hi = 0.03;  // the largest radius it says no for, by bisection
    for (int k = 0; k < 30; ++k) (scene.mayHaveMaterialNear(p, 0.5 * (lo + hi)) ? hi : lo) = 0.5 * (lo + hi);
    for (int k = 0; k < 400; ++k) {
      const glm::dvec3 u(unit(rng), unit(rng), unit(rng));
      if (glm::length(u) > 1.0 || glm::length(u) < 1e-3) continue;
      const glm::dvec3 q = p + lo * (k % 4 ? glm::normalize(u) : u);  // mostly on the sphere, some inside
      ASSERT_LE(scene.field(q), 0.0) << "material " << glm::length(q - p) << " m from a point said to have none within " << lo;
    }
  }
  EXPECT_GT(no, 60) << "the cull should say no for much of the space round the tooth";
  EXPECT_TRUE(scene.mayHaveMaterialNear(glm::dvec3(place * glm::dvec4(0.0, 0.0, 0.0, 1.0)), 0.0));
}

// The stored densities summarised for `millsim check` (VoxelVolume::densitySummary).
constexpr float kSummaryAir = -1000.f;

// Summed leaf by leaf on TBB's threads, in chunks of leaves: the same figures
// as one walk over every stored value (the grid spans many chunks; a reader's
// active tile becomes voxels too).
TEST(VoxelVolumeDensitySummary, TheParallelSummaryEqualsOneWalk) {
  VoxelVolume::Grid::Ptr grid = VoxelVolume::Grid::create(kSummaryAir);
  grid->tree().addTile(2, openvdb::Coord(0), 500.f, true);  // 128³ voxels of one value
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> at(128, 400);
  std::uniform_real_distribution<float> value(-900.f, 3000.f);
  for (int i = 0; i < 200000; ++i) grid->tree().setValueOn(openvdb::Coord(at(rng), at(rng), at(rng)), value(rng));
  const VoxelVolume vol(grid, glm::ivec3(401), glm::dvec3(1e-4), kSummaryAir);
  ASSERT_GT(vol.grid().tree().leafCount(), 10000u) << "many chunks of leaves";
  std::vector<float> all;
  for (auto it = vol.grid().cbeginValueOn(); it; ++it)
    for (openvdb::Index64 n = 0; n < it.getVoxelCount(); ++n) all.push_back(*it);
  std::sort(all.begin(), all.end());
  ASSERT_GT(all.size(), std::size_t(128 * 128 * 128)) << "the tile's voxels";
  const VoxelVolume::DensitySummary s = vol.densitySummary(700.f);
  EXPECT_EQ(s.voxels, all.size());
  EXPECT_EQ(s.voxels, vol.activeVoxels());
  EXPECT_EQ(s.aboveIso, std::uint64_t(all.end() - std::upper_bound(all.begin(), all.end(), 700.f)));
  EXPECT_EQ(s.min, all.front());
  EXPECT_EQ(s.max, all.back());
  const float bin = (all.back() - all.front()) / 4096.f;  // percentiles are bin centres
  EXPECT_NEAR(s.p10, all[all.size() / 10], bin);
  EXPECT_NEAR(s.p50, all[all.size() / 2], bin);
  EXPECT_NEAR(s.p90, all[all.size() * 9 / 10], bin);
}

TEST(VoxelVolumeDensitySummary, CountsRangeAndPercentilesOfTheStoredDensities) {
  // 1000 voxels of 1, 2, ..., 1000 and as many of air, which is not stored.
  const glm::ivec3 d(20, 10, 10);
  std::vector<float> v(std::size_t(d.x) * d.y * d.z, kSummaryAir);
  for (std::size_t i = 0; i < 1000; ++i) v[2 * i] = float(i + 1);
  const VoxelVolume vol = VoxelVolume::fromDense(v.data(), d, glm::dvec3(1e-4), kSummaryAir);
  const VoxelVolume::DensitySummary s = vol.densitySummary(700.f);
  EXPECT_EQ(s.voxels, 1000u);
  EXPECT_EQ(s.aboveIso, 300u);
  EXPECT_EQ(s.min, 1.f);
  EXPECT_EQ(s.max, 1000.f);
  const float bin = 999.f / 4096.f;  // percentiles are bin centres
  EXPECT_NEAR(s.p10, 100.f, bin);
  EXPECT_NEAR(s.p50, 500.f, bin);
  EXPECT_NEAR(s.p90, 900.f, bin);
  EXPECT_EQ(VoxelVolume::fromDense(std::vector<float>(8, kSummaryAir).data(), glm::ivec3(2), glm::dvec3(1e-4), kSummaryAir).densitySummary(0.f).voxels,
            0u);
}
