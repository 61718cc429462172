#pragma once
// MaterialBlocks: how far, in 8³ blocks, each block of a volume lies from the
// nearest block that may hold material. Air is the grid's background and
// material lives only in leaf nodes (VoxelVolume), so a block without a leaf
// is air. One byte per block, built once: milling only removes material, so
// the distances stay a safe (never too large) bound without updates. A
// renderer asks it before sampling a region (HapticScene::mayHaveMaterialNear)
// and skips the samples where the tool is far from everything.
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace millsim {

class VoxelVolume;

class MaterialBlocks {
public:
  MaterialBlocks() = default;
  explicit MaterialBlocks(const VoxelVolume& volume);

  // False only if nothing sampled within `radius` voxels of the index-space
  // point `p` (trilinearly, so one voxel further) can read a material voxel.
  bool mayHaveMaterialNear(const glm::dvec3& p, double radius) const;

private:
  glm::ivec3 blocks_{0};
  std::vector<std::uint8_t> distance_;  // Chebyshev distance in blocks to a leaf, capped at 255
};

}  // namespace millsim
