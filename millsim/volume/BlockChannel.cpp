#include "millsim/volume/BlockChannel.h"

#include "millsim/volume/VoxelVolume.h"

namespace millsim {

namespace {
// Index of voxel (x, y, z) inside a block, x fastest.
constexpr int cell(int x, int y, int z) { return (z * 8 + y) * 8 + x; }
openvdb::Coord coord(const BlockOrigin& o) { return {o.x, o.y, o.z}; }
}  // namespace

bool BlockChannel::tryPush(const VoxelVolume& volume, const BlockOrigin& origin) {
  const std::size_t head = head_.load(std::memory_order_relaxed);
  const std::size_t next = (head + 1) % slots_.size();
  if (next == tail_.load(std::memory_order_acquire)) return false;
  BlockUpdate& slot = slots_[head];
  slot.origin = origin;
  if (const auto* leaf = volume.grid().tree().probeConstLeaf(coord(origin))) {
    // Straight from the leaf's buffer (z fastest there: x·64 + y·8 + z), not
    // through getValue per voxel (that was 5.5 % of the haptic thread's
    // instructions in #2's §8.2 replay, all of it in milling frames).
    const float* data = leaf->buffer().data();
    for (int z = 0; z < 8; ++z)
      for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) slot.values[cell(x, y, z)] = data[(x << 6) + (y << 3) + z];
  } else {
    slot.values.fill(volume.airValue());  // an all-air block has no leaf
  }
  head_.store(next, std::memory_order_release);
  return true;
}

BlockPublisher::BlockPublisher(const VoxelVolume& volume, BlockChannel& channel)
    : volume_(volume), channel_(channel), pending_(volume.dims()) {}

std::size_t BlockPublisher::publish(const std::vector<BlockOrigin>& changed) {
  for (const auto& o : changed) pending_.markVoxel(o.x, o.y, o.z);
  std::size_t pushed = 0;
  for (const auto& o : pending_.origins()) {
    if (!channel_.tryPush(volume_, o)) break;
    ++pushed;
  }
  pending_.dropFront(pushed);
  return pending_.origins().size();
}

VolumeReplica::VolumeReplica(const VoxelVolume& source)
    : volume_(std::make_unique<VoxelVolume>(source.grid().deepCopy(), source.dims(), source.voxelSize(),
                                            source.airValue())),
      changed_(source.dims()) {}

VolumeReplica::~VolumeReplica() = default;

const std::vector<BlockOrigin>& VolumeReplica::apply(BlockChannel& channel) {
  changed_.clear();
  auto acc = volume_->grid().getAccessor();
  const float air = volume_->airValue();
  channel.drain([&](const BlockUpdate& u) {
    for (int z = 0; z < 8; ++z)
      for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
          const openvdb::Coord c = coord(u.origin) + openvdb::Coord(x, y, z);
          const float v = u.values[cell(x, y, z)];
          // Only touch voxels that differ: unchanged air stays sparse.
          if (acc.getValue(c) != v && !(v <= air && !acc.isValueOn(c))) acc.setValueOnly(c, v);
        }
    changed_.markVoxel(u.origin.x, u.origin.y, u.origin.z);
  });
  return changed_.origins();
}

}  // namespace millsim
