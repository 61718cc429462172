#include "millsim/volume/MaterialBlocks.h"

#include <algorithm>
#include <cmath>
#include <deque>

#include "millsim/volume/DirtyBlocks.h"
#include "millsim/volume/VoxelVolume.h"

namespace millsim {

MaterialBlocks::MaterialBlocks(const VoxelVolume& volume)
    : blocks_((volume.dims() + DirtyBlocks::kSize - 1) / DirtyBlocks::kSize),
      distance_(std::size_t(blocks_.x) * blocks_.y * blocks_.z, 255) {
  auto index = [&](int x, int y, int z) { return (std::size_t(z) * blocks_.y + y) * blocks_.x + x; };
  // A breadth-first walk over the 26 neighbours from every block holding a
  // leaf gives the Chebyshev distance in blocks.
  std::deque<glm::ivec3> queue;
  for (auto leaf = volume.grid().tree().cbeginLeaf(); leaf; ++leaf) {
    const openvdb::Coord o = leaf->origin();
    const glm::ivec3 b(o.x() >> DirtyBlocks::kLog2, o.y() >> DirtyBlocks::kLog2, o.z() >> DirtyBlocks::kLog2);
    if (b.x < 0 || b.y < 0 || b.z < 0 || b.x >= blocks_.x || b.y >= blocks_.y || b.z >= blocks_.z) continue;
    if (distance_[index(b.x, b.y, b.z)] == 0) continue;
    distance_[index(b.x, b.y, b.z)] = 0;
    queue.push_back(b);
  }
  // A constant tile above air (a .vdb's; VoxelVolume voxelises active ones)
  // may be material too: all of its blocks are.
  auto it = volume.grid().tree().cbeginValueAll();
  it.setMaxDepth(VoxelVolume::Grid::TreeType::ValueAllCIter::LEAF_DEPTH - 1);
  for (; it; ++it) {
    if (!(*it > volume.airValue())) continue;
    const openvdb::CoordBBox box = it.getBoundingBox();
    constexpr int s = DirtyBlocks::kLog2;
    for (int z = std::max(0, box.min().z() >> s); z <= std::min(blocks_.z - 1, box.max().z() >> s); ++z)
      for (int y = std::max(0, box.min().y() >> s); y <= std::min(blocks_.y - 1, box.max().y() >> s); ++y)
        for (int x = std::max(0, box.min().x() >> s); x <= std::min(blocks_.x - 1, box.max().x() >> s); ++x)
          if (distance_[index(x, y, z)] != 0) distance_[index(x, y, z)] = 0, queue.emplace_back(x, y, z);
  }
  while (!queue.empty()) {
    const glm::ivec3 b = queue.front();
    queue.pop_front();
    const int next = distance_[index(b.x, b.y, b.z)] + 1;
    if (next >= 255) continue;
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const glm::ivec3 n = b + glm::ivec3(dx, dy, dz);
          if (n.x < 0 || n.y < 0 || n.z < 0 || n.x >= blocks_.x || n.y >= blocks_.y || n.z >= blocks_.z) continue;
          std::uint8_t& d = distance_[index(n.x, n.y, n.z)];
          if (d <= next) continue;
          d = std::uint8_t(next);
          queue.push_back(n);
        }
  }
}

bool MaterialBlocks::mayHaveMaterialNear(const glm::dvec3& p, double radius) const {
  if (distance_.empty()) return false;  // no voxels at all
  if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) && std::isfinite(radius))) return true;
  // A point outside the grid is no nearer to a leaf than its clamped block is.
  auto block = [](double v, int n) {
    return int(std::clamp(std::floor(v / DirtyBlocks::kSize), 0.0, double(n - 1)));
  };
  const int bx = block(p.x, blocks_.x), by = block(p.y, blocks_.y), bz = block(p.z, blocks_.z);
  const int d = distance_[(std::size_t(bz) * blocks_.y + by) * blocks_.x + bx];
  if (d == 0) return true;
  // Every voxel of a block d blocks away is at least (d − 1)·8 voxels away
  // along some axis; a trilinear sample reads voxels less than one voxel away.
  return double(d - 1) * DirtyBlocks::kSize < radius + 1.0;
}

}  // namespace millsim
