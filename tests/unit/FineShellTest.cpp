// Issue 44's must-holds for the point shell at micro-CT voxels: on the tooth
// phantom at 50 µm (label unit) and 25 µm (the tests named *Soak*, label
// soak), a point costs at most 200 bytes at scales 1 to 3 (Barbic's default
// shell, scale 1, and its coarse fallback at 2; the figures), and
// after random milling — paced by a budget, as VolumeObject.millingBudget
// walks it — the shells at scales 1, 2, 3 and 6 kept current piece by piece
// equal a rebuild, points and normals. (Scale 6, the fallback of
// pointShellScale 3, costs about 270 bytes a point at 50 µm: its buckets'
// fixed part is shared by few points. Not held here.)
#include <gtest/gtest.h>

#include <random>

#include "millsim/volume/PointShell.h"
#include "millsim/volume/ToothPhantom.h"
#include "millsim/volume/VoxelScene.h"

using namespace millsim;

namespace {

void fineShellHolds(int micrometres) {
  ToothPhantomOptions o;
  o.dims = o.dims * (100 / micrometres);
  o.voxelSize = double(micrometres) * 1e-6;
  VoxelVolume v = makeToothPhantom(o);
  VoxelScene scene;
  scene.addVolume(v, glm::dmat4(1.0), 700.0);
  scene.volume(0).millingBudget = 1000;
  const int scales[] = {1, 2, 3, 6};
  for (int s : scales) {
    const PointShell& shell = scene.shell(0, s);
    ASSERT_GT(shell.size(), 1000u) << "scale " << s;
    if (s <= 3) {
      EXPECT_LE(double(shell.memoryBytes()) / double(shell.size()), 200.0)
          << "scale " << s << ": " << shell.size() << " points, " << shell.memoryBytes() << " bytes";
    }
  }
  // Random stamps of burrs from 0.3 to 1 mm about the occlusal surface (the
  // phantom's top is near y = 9.9 mm), each walked to its end over frames
  // that do not cut, the shells asked for now and then as renderers do.
  std::mt19937 rng(44);
  std::uniform_real_distribution<double> across(-2.5e-3, 2.5e-3), depth(8.0e-3, 10.5e-3), radius(0.3e-3, 1.0e-3);
  double removed = 0.0;
  long frames = 0;
  for (int stamp = 0; stamp < 120; ++stamp) {
    removed += scene.mill({across(rng), depth(rng), across(rng)}, radius(rng));
    while (scene.millingPending()) {
      removed += scene.continueMilling();
      if (++frames % 5 == 0) scene.pointShell(0, 1);
    }
  }
  EXPECT_GT(removed, 0.0);
  EXPECT_GT(frames, 120) << "the budget walked the stamps over frames";
  for (int s : scales) {
    const auto a = scene.shell(0, s).points(), b = PointShell(v, 700.f, s).points();
    ASSERT_EQ(a.size(), b.size()) << "scale " << s;
    for (std::size_t i = 0; i < a.size(); ++i) {
      ASSERT_EQ(a[i].position, b[i].position) << "scale " << s << " point " << i;
      ASSERT_EQ(a[i].normal, b[i].normal) << "scale " << s << " point " << i;
    }
  }
}

}  // namespace

TEST(FineShell, At50MicronsAPointCostsAtMost200BytesAndMillingEqualsARebuild) { fineShellHolds(50); }
TEST(FineShell, SoakAt25MicronsAPointCostsAtMost200BytesAndMillingEqualsARebuild) { fineShellHolds(25); }
