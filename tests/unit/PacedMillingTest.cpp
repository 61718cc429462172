// Paced milling (Miller::queue / work, VolumeObject.millingBudget): a stamp
// walked over several frames within a budget of densities read leaves the
// same grid as stamping it at once, never reads much past its budget, and
// a frame that does not cut carries on with what was left.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "millsim/haptics/BurrHead.h"
#include "millsim/volume/Milling.h"
#include "millsim/volume/VoxelScene.h"
#include "millsim/volume/VoxelVolume.h"

using namespace millsim;

namespace {

constexpr float kAir = -1000.f, kIso = 700.f;

// A noisy slab below j = 20, denser with depth: stamps change different
// amounts at different places, so a dropped or repeated row shows.
VoxelVolume slab(glm::ivec3 n, glm::dvec3 h) {
  std::vector<float> values(std::size_t(n.x) * n.y * n.z);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> noise(-300.f, 300.f);
  for (int k = 0; k < n.z; ++k)
    for (int j = 0; j < n.y; ++j)
      for (int i = 0; i < n.x; ++i)
        values[(std::size_t(k) * n.y + j) * n.x + i] =
            j < 20 ? std::min(3000.f, 1200.f + 100.f * float(20 - j) + noise(rng)) : kAir;
  return VoxelVolume::fromDense(values.data(), n, h, kAir);
}

int differingVoxels(const VoxelVolume& a, const VoxelVolume& b) {
  const glm::ivec3 n = a.dims();
  int differ = 0;
  for (int k = 0; k < n.z; ++k)
    for (int j = 0; j < n.y; ++j)
      for (int i = 0; i < n.x; ++i) {
        const openvdb::Coord at(i, j, k);
        differ += a.grid().tree().getValue(at) != b.grid().tree().getValue(at);
      }
  return differ;
}

// Where the burr is at stamp s (index space): creeping down, holding, turning
// its head, and once jumping.
struct Path {
  std::mt19937 rng{17};
  glm::dvec3 c{20.0, 21.0, 22.0};
  glm::dvec3 next(int s) {
    std::uniform_real_distribution<double> step(-0.3, 0.3);
    if (s == 40) c = glm::dvec3(12.0, 17.0, 30.0);
    else if (s % 9 != 4) c += glm::dvec3(step(rng), step(rng) - 0.1, step(rng));
    return c;
  }
};

}  // namespace

// Every stamp walked to its end over many small budgets, round and shaped
// heads, equals the same stamps made at once: the same grid bit for bit, and
// the same removed volume up to the order of its sum.
TEST(PacedMilling, WalkingAStampOverManyCallsLeavesTheSameGrid) {
  const glm::ivec3 n(40, 36, 44);
  const glm::dvec3 h(1e-4, 0.8e-4, 1.2e-4);  // not cubic, as the settled skip weighs each axis
  VoxelVolume paced = slab(n, h), atOnce = slab(n, h);
  Miller pacedMiller(paced, kIso), atOnceMiller(atOnce, kIso);
  BurrHead taper{BurrShape::Taper, 4e-4, 9e-4, 2e-4};
  Path path;
  double removedPaced = 0.0, removedAtOnce = 0.0;
  long calls = 0;
  for (int s = 0; s < 80; ++s) {
    const glm::dvec3 c = path.next(s);
    const glm::dvec3 axis = glm::normalize(glm::dvec3(0.2, 1.0, 0.1 * (s % 3)));
    DirtyBlocks dirty(n);
    const bool round = s % 10 != 7;
    if (round) {
      pacedMiller.queue(paced.indexToLocal(c), 5e-4);
      removedAtOnce += atOnceMiller.stamp(atOnce.indexToLocal(c), 5e-4, dirty).removedVolume;
    } else {
      pacedMiller.queue(paced.indexToLocal(c), axis, taper);
      removedAtOnce += atOnceMiller.stamp(atOnce.indexToLocal(c), axis, taper, dirty).removedVolume;
    }
    // Budgets from one row to a few hundred densities, until the stamp is done.
    const long budget = 1 + (s * 37) % 300;
    while (pacedMiller.busy()) {
      DirtyBlocks d(n);
      removedPaced += pacedMiller.work(budget, d).removedVolume;
      ++calls;
    }
  }
  EXPECT_GT(calls, 400) << "the stamps were walked in many pieces";
  EXPECT_EQ(differingVoxels(paced, atOnce), 0);
  EXPECT_GT(removedAtOnce, 0.0);
  EXPECT_NEAR(removedPaced, removedAtOnce, 1e-9 * removedAtOnce);
  EXPECT_NEAR(pacedMiller.totalRemoved(), atOnceMiller.totalRemoved(), 1e-9 * removedAtOnce);
}

// A call reads at most its budget and the rest of the row it stopped in; a
// stamp queued while another is walked waits, and a newer one replaces it.
TEST(PacedMilling, ACallStaysWithinItsBudgetAndTheNewestStampWins) {
  const glm::ivec3 n(40, 36, 44);
  const glm::dvec3 h(1e-4);
  VoxelVolume paced = slab(n, h), atOnce = slab(n, h);
  Miller pacedMiller(paced, kIso), atOnceMiller(atOnce, kIso);
  const double radius = 6e-4;
  // The longest row a stamp of this radius reads, and one for the row's start.
  const long rowMost = 2 * long(radius / 1e-4 + 2.0) + 2;
  const glm::dvec3 a(20.0, 19.0, 22.0), b(20.5, 18.7, 22.0), c(21.0, 18.4, 22.3);
  pacedMiller.queue(paced.indexToLocal(a), radius);
  DirtyBlocks d(n);
  const long budget = 150;
  StampResult first = pacedMiller.work(budget, d);
  EXPECT_GT(first.voxelsRead, 0);
  EXPECT_LE(first.voxelsRead, budget + rowMost);
  ASSERT_TRUE(pacedMiller.busy()) << "a stamp this size takes more than one call";
  pacedMiller.queue(paced.indexToLocal(b), radius);  // waits for a
  pacedMiller.queue(paced.indexToLocal(c), radius);  // replaces b
  long most = 0;
  while (pacedMiller.busy()) {
    DirtyBlocks e(n);
    most = std::max(most, pacedMiller.work(budget, e).voxelsRead);
  }
  EXPECT_LE(most, budget + rowMost);
  DirtyBlocks e(n);
  atOnceMiller.stamp(atOnce.indexToLocal(a), radius, e);
  atOnceMiller.stamp(atOnce.indexToLocal(c), radius, e);
  EXPECT_EQ(differingVoxels(paced, atOnce), 0) << "a, then c: b was replaced before it began";
  // Without a budget a call walks everything queued.
  pacedMiller.queue(paced.indexToLocal(a + glm::dvec3(0.0, -2.0, 0.0)), radius);
  EXPECT_GT(pacedMiller.work(0, e).voxelsRead, budget + rowMost);
  EXPECT_FALSE(pacedMiller.busy());
}

// VoxelScene with a millingBudget: mill() walks at most the budget, a frame
// that does not cut (continueMilling) finishes the stamp, the field reads
// the whole stamp from the first frame, and the scene's sampler and dirty
// blocks follow every piece.
TEST(PacedMilling, AFrameThatDoesNotCutFinishesTheStamp) {
  const glm::ivec3 n(40, 36, 44);
  const glm::dvec3 h(1e-4);
  VoxelVolume paced = slab(n, h), atOnce = slab(n, h);
  VoxelScene pacedScene, atOnceScene;
  pacedScene.addVolume(paced, glm::dmat4(1.0), kIso);
  atOnceScene.addVolume(atOnce, glm::dmat4(1.0), kIso);
  pacedScene.volume(0).millingBudget = 200;
  const glm::dvec3 centre = paced.indexToLocal(glm::dvec3(20.0, 19.5, 22.0));
  pacedScene.focus(centre, 1e-3);
  const double removedAtOnce = atOnceScene.mill(centre, 6e-4);
  double removed = pacedScene.mill(centre, 6e-4);
  ASSERT_TRUE(pacedScene.millingPending());
  EXPECT_LT(removed, removedAtOnce);
  // The grid holds a piece of the stamp, but the field a renderer reads is
  // the whole stamp's already (VolumeSampler::setPendingCuts).
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(-8e-4, 8e-4);
  auto differingSamples = [&] {
    int differ = 0;
    for (int i = 0; i < 2000; ++i) {
      const glm::dvec3 p = centre + glm::dvec3(u(rng), u(rng), u(rng));
      differ += pacedScene.field(p) != atOnceScene.field(p);
      differ += pacedScene.gradient(p) != atOnceScene.gradient(p);
    }
    return differ;
  };
  EXPECT_EQ(differingSamples(), 0) << "the renderers feel the stamp the walk has not finished";
  EXPECT_NE(differingVoxels(paced, atOnce), 0) << "while the grid does not hold all of it yet";
  int frames = 1;
  std::uint64_t epoch = pacedScene.volume(0).millEpoch;
  while (pacedScene.millingPending()) {
    removed += pacedScene.continueMilling();
    ++frames;
    ASSERT_LT(frames, 1000);
  }
  EXPECT_GT(frames, 3);
  EXPECT_GT(pacedScene.volume(0).millEpoch, epoch) << "the later pieces were published";
  EXPECT_NEAR(removed, removedAtOnce, 1e-9 * removedAtOnce);
  EXPECT_EQ(differingVoxels(paced, atOnce), 0);
  EXPECT_EQ(differingSamples(), 0) << "the sampler's window was refreshed for every piece";
  EXPECT_EQ(pacedScene.continueMilling(), 0.0);
}
