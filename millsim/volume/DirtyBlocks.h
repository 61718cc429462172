#pragma once
// DirtyBlocks: the set of 8³ voxel blocks (OpenVDB leaf nodes) changed since
// the consumer last took them. A bitset over the volume's block grid plus a
// list with capacity for every block, so marking never allocates.
#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

namespace millsim {

// An 8³ block by the index of its first voxel (an OpenVDB leaf origin).
using BlockOrigin = glm::ivec3;

class DirtyBlocks {
public:
  static constexpr int kLog2 = 3;  // 8³ voxels: OpenVDB's leaf size
  static constexpr int kSize = 1 << kLog2;

  DirtyBlocks() = default;
  explicit DirtyBlocks(glm::ivec3 dims)
      : blocks_((dims + kSize - 1) / kSize),
        bits_(std::size_t(blocks_.x) * blocks_.y * blocks_.z, false) {
    list_.reserve(bits_.size());
  }

  // Marks the block holding voxel (i, j, k); voxels outside the volume are ignored.
  void markVoxel(int i, int j, int k) { markRun(i, i, j, k); }
  // Marks voxels iLo..iHi of row (j, k), which lie in one block, as markVoxel
  // would one by one: the miller marks a row's changed voxels of a block at
  // once (one call a voxel was a tenth of a stamp's instructions).
  void markRun(int iLo, int iHi, int j, int k) {
    const int bx = iLo >> kLog2, by = j >> kLog2, bz = k >> kLog2;
    if (iLo < 0 || j < 0 || k < 0 || bx >= blocks_.x || by >= blocks_.y || bz >= blocks_.z) return;
    voxelLo_ = glm::min(voxelLo_, glm::ivec3(iLo, j, k)), voxelHi_ = glm::max(voxelHi_, glm::ivec3(iHi, j, k));
    const std::size_t idx = (std::size_t(bz) * blocks_.y + by) * blocks_.x + bx;
    if (bits_[idx]) return;
    bits_[idx] = true;
    list_.emplace_back(bx << kLog2, by << kLog2, bz << kLog2);
  }

  // Adds the blocks and the voxel box another set (of a volume with the same
  // dimensions) marked: a consumer that merges several calls' changes at once.
  void add(const DirtyBlocks& other) {
    for (const BlockOrigin& o : other.list_) {
      const std::size_t idx = index(o);
      if (bits_[idx]) continue;
      bits_[idx] = true;
      list_.push_back(o);
    }
    voxelLo_ = glm::min(voxelLo_, other.voxelLo_), voxelHi_ = glm::max(voxelHi_, other.voxelHi_);
  }
  // Whether the block holding voxel (i, j, k) is marked (false outside the volume).
  bool markedVoxel(int i, int j, int k) const {
    const int bx = i >> kLog2, by = j >> kLog2, bz = k >> kLog2;
    if (i < 0 || j < 0 || k < 0 || bx >= blocks_.x || by >= blocks_.y || bz >= blocks_.z) return false;
    return bits_[(std::size_t(bz) * blocks_.y + by) * blocks_.x + bx];
  }

  // Leaf origins marked so far, in the order they were first marked.
  const std::vector<BlockOrigin>& origins() const { return list_; }
  bool empty() const { return list_.empty(); }
  // Bounding box (inclusive, voxel indices) of every voxel marked since the
  // last clear(): far tighter than the blocks, so consumers such as the point
  // shell can recompute only what a burr stamp touched. dropFront() keeps it
  // (a superset stays correct). Empty (lo > hi) when nothing is marked.
  glm::ivec3 voxelLo() const { return voxelLo_; }
  glm::ivec3 voxelHi() const { return voxelHi_; }
  // Forgets the first n marked blocks, keeping the rest in order (in place).
  void dropFront(std::size_t n) {
    n = std::min(n, list_.size());
    for (std::size_t i = 0; i < n; ++i) unmark(list_[i]);
    list_.erase(list_.begin(), list_.begin() + static_cast<std::ptrdiff_t>(n));
  }
  void clear() {
    for (const auto& c : list_) unmark(c);
    list_.clear();
    voxelLo_ = glm::ivec3(std::numeric_limits<int>::max()), voxelHi_ = glm::ivec3(std::numeric_limits<int>::min());
  }

private:
  std::size_t index(const BlockOrigin& c) const {
    return (std::size_t(c.z >> kLog2) * blocks_.y + (c.y >> kLog2)) * blocks_.x + (c.x >> kLog2);
  }
  void unmark(const BlockOrigin& c) { bits_[index(c)] = false; }
  glm::ivec3 blocks_{0};
  std::vector<bool> bits_;
  std::vector<BlockOrigin> list_;
  glm::ivec3 voxelLo_{std::numeric_limits<int>::max()};
  glm::ivec3 voxelHi_{std::numeric_limits<int>::min()};
};

}  // namespace millsim
