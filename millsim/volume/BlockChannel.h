#pragma once
// How milled voxels reach the graphics side without a data race and without
// the haptic thread ever waiting.
//
// The haptic thread is the only writer of a VolumeObject's grid. After a stamp
// it publishes every changed 8³ block — a copy of its 512 values — into a
// fixed-size single-producer/single-consumer ring (BlockChannel). The graphics
// side owns a VolumeReplica, a deep copy of the grid made before milling
// starts, and applies the blocks it drains to it; it meshes from the replica.
// When the ring is full, the publisher keeps the blocks pending and retries on
// the next frame (copying the then-current values), so nothing is lost and
// nothing blocks. No step allocates after construction.
#include <array>
#include <atomic>
#include <memory>
#include <vector>

#include "millsim/volume/DirtyBlocks.h"

namespace millsim {

class VoxelVolume;

struct BlockUpdate {
  BlockOrigin origin;
  std::array<float, 512> values;  // x fastest within the block
};

class BlockChannel {
public:
  explicit BlockChannel(std::size_t capacity) : slots_(capacity + 1) {}

  // Producer: copies the block at `origin` out of `volume`. False when full.
  bool tryPush(const VoxelVolume& volume, const BlockOrigin& origin);
  // Consumer: calls apply(const BlockUpdate&) for every block published so far; returns how many.
  template <class Apply> std::size_t drain(Apply&& apply) {
    std::size_t n = 0;
    std::size_t tail = tail_.load(std::memory_order_relaxed);
    const std::size_t head = head_.load(std::memory_order_acquire);
    while (tail != head) {
      apply(slots_[tail]);
      tail = (tail + 1) % slots_.size();
      ++n;
    }
    tail_.store(tail, std::memory_order_release);
    return n;
  }
  std::size_t capacity() const { return slots_.size() - 1; }

private:
  std::vector<BlockUpdate> slots_;
  alignas(64) std::atomic<std::size_t> head_{0};  // next slot the producer writes
  alignas(64) std::atomic<std::size_t> tail_{0};  // next slot the consumer reads
};

// The haptic side: remembers blocks not yet published and publishes what fits.
class BlockPublisher {
public:
  BlockPublisher(const VoxelVolume& volume, BlockChannel& channel);
  // Adds the newly changed blocks, then publishes as many pending blocks as the
  // channel takes. Returns the number still pending.
  std::size_t publish(const std::vector<BlockOrigin>& changed);
  std::size_t pending() const { return pending_.origins().size(); }

private:
  const VoxelVolume& volume_;
  BlockChannel& channel_;
  DirtyBlocks pending_;
};

// The graphics side's own copy of the voxels.
class VolumeReplica {
public:
  explicit VolumeReplica(const VoxelVolume& source);  // deep copy; call before milling starts
  ~VolumeReplica();
  // Applies everything published; returns the origins of the changed blocks
  // (valid until the next call).
  const std::vector<BlockOrigin>& apply(BlockChannel& channel);
  const VoxelVolume& volume() const { return *volume_; }

private:
  std::unique_ptr<VoxelVolume> volume_;
  DirtyBlocks changed_;
};

}  // namespace millsim
