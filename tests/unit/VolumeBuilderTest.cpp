// VolumeBuilder: a volume built a slab at a time means what its densities say,
// voxel for voxel, however the values arrive, with no leaf where there is no
// material; bad values are refused at their voxel.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <tuple>
#include <vector>

#include <glm/geometric.hpp>

#include "millsim/volume/VolumeBuilder.h"
#include "millsim/volume/VoxelVolume.h"

using namespace millsim;

namespace {

constexpr float kAir = -1000.f;
const glm::dvec3 kVoxel(1e-4);

// Densities with material in scattered blobs, air elsewhere, values exactly at air too.
std::vector<float> blobs(glm::ivec3 d, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  std::vector<float> v(std::size_t(d.x) * d.y * d.z, kAir);
  for (int b = 0; b < 6; ++b) {
    const glm::dvec3 c(u(rng) * d.x, u(rng) * d.y, u(rng) * d.z);
    const double r = 1.5 + 4.0 * u(rng);
    for (int k = 0; k < d.z; ++k)
      for (int j = 0; j < d.y; ++j)
        for (int i = 0; i < d.x; ++i)
          if (glm::length(glm::dvec3(i, j, k) - c) < r) v[(std::size_t(k) * d.y + j) * d.x + i] = 200.f + 1000.f * u(rng);
  }
  for (std::size_t i = 0; i < v.size(); i += 97) v[i] = kAir;        // exactly air: not stored
  for (std::size_t i = 5; i < v.size(); i += 89) v[i] = kAir - 50.f;  // below air: not stored
  return v;
}

VoxelVolume buildInChunks(const std::vector<float>& v, glm::ivec3 d, unsigned seed) {
  VolumeBuilder b(d, kVoxel, kAir, "chunks");
  std::mt19937 rng(seed);
  std::size_t at = 0;
  while (at < v.size()) {
    const std::size_t n = std::min<std::size_t>(v.size() - at, 1 + rng() % 3000);
    if (rng() % 2) {
      b.append(v.data() + at, n);
    } else {  // through next()/advance(), as the readers' converters write
      std::size_t left = n;
      while (left > 0) {
        const std::size_t k = std::min(left, b.room());
        std::copy(v.begin() + std::ptrdiff_t(at + n - left), v.begin() + std::ptrdiff_t(at + n - left + k), b.next());
        b.advance(k);
        left -= k;
      }
    }
    at += n;
  }
  EXPECT_EQ(b.room(), 0u);
  return b.finish();
}

}  // namespace

TEST(VolumeBuilder, EveryVoxelMeansItsDensityWithNoLeafWithoutMaterial) {
  // z below one slab, exactly one, and not a multiple of the slab's 8 slices.
  for (const glm::ivec3 d : {glm::ivec3(13, 9, 5), glm::ivec3(16, 16, 8), glm::ivec3(21, 17, 27)}) {
    const std::vector<float> v = blobs(d, unsigned(d.z));
    const VoxelVolume vol = buildInChunks(v, d, 7);
    std::uint64_t material = 0;
    std::set<std::tuple<int, int, int>> blocks;  // 8³ leaves that hold material
    for (int k = 0; k < d.z; ++k)
      for (int j = 0; j < d.y; ++j)
        for (int i = 0; i < d.x; ++i) {
          const float want = v[(std::size_t(k) * d.y + j) * d.x + i];
          ASSERT_EQ(vol.valueAt(i, j, k), want > kAir ? want : kAir) << "voxel " << i << ", " << j << ", " << k;
          if (want > kAir) ++material, blocks.insert({i / 8, j / 8, k / 8});
        }
    EXPECT_EQ(vol.activeVoxels(), material);
    EXPECT_EQ(vol.grid().tree().leafCount(), blocks.size()) << "a leaf for each 8³ block with material, no other";
    // However the values arrive, the same volume.
    const VoxelVolume once = VoxelVolume::fromDense(v.data(), d, kVoxel, kAir);
    EXPECT_EQ(once.contentHash(), vol.contentHash());
    EXPECT_EQ(once.memoryBytes(), vol.memoryBytes());
  }
}

TEST(VolumeBuilder, RefusesANonFiniteDensityAtItsVoxelAndAnUnfinishedVolume) {
  const glm::ivec3 d(6, 5, 20);
  std::vector<float> v(std::size_t(d.x) * d.y * d.z, 0.f);
  v[(std::size_t(17) * d.y + 3) * d.x + 4] = std::numeric_limits<float>::quiet_NaN();  // in the third slab
  VolumeBuilder b(d, kVoxel, kAir, "n.nrrd");
  try {
    b.append(v.data(), v.size());
    b.finish();
    FAIL() << "a NaN density was accepted";
  } catch (const VolumeError& e) {
    EXPECT_STREQ(e.what(), "n.nrrd: voxel (4, 3, 17) has the density nan; a density must be a finite number");
  }
  VolumeBuilder part(d, kVoxel, kAir, "h.nrrd");
  part.append(v.data(), 100);
  try {
    part.finish();
    FAIL() << "a volume with 100 of its 600 voxels given was accepted";
  } catch (const VolumeError& e) {
    EXPECT_STREQ(e.what(), "h.nrrd: 100 of its 600 voxels were given a density");
  }
  EXPECT_THROW(VolumeBuilder(glm::ivec3(0, 4, 4), kVoxel, kAir, "z.nrrd"), VolumeError);
}
