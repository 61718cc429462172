#include "millsim/volume/VolumeBuilder.h"

#include <cmath>
#include <cstring>
#include <utility>

namespace millsim {

namespace {
// Slices per slab: one leaf node deep, so a slab fills whole leaves along z
// and each leaf is touched by one slab only.
constexpr int kSlabSlices = 8;
}  // namespace

VolumeBuilder::VolumeBuilder(glm::ivec3 dims, glm::dvec3 voxelSize, float airValue, std::string source)
    : dims_(dims), voxelSize_(voxelSize), airValue_(airValue), source_(std::move(source)) {
  checkVolumeShape(source_, dims, voxelSize);
  total_ = std::size_t(dims.x) * std::size_t(dims.y) * std::size_t(dims.z);
  slab_.resize(std::size_t(dims.x) * std::size_t(dims.y) * std::size_t(std::min(dims.z, kSlabSlices)));
  openvdb::initialize();  // idempotent and thread-safe
  grid_ = VoxelVolume::Grid::create(airValue);
  grid_->setName("density");
}

VolumeBuilder::~VolumeBuilder() = default;

void VolumeBuilder::advance(std::size_t n) {
  n = std::min(n, room());
  inSlab_ += n, done_ += n;
  if (inSlab_ == slab_.size()) flushSlab();
}

void VolumeBuilder::append(const float* values, std::size_t count) {
  while (count > 0 && room() > 0) {
    const std::size_t n = std::min(count, room());
    std::memcpy(next(), values, n * sizeof(float));
    values += n, count -= n;
    advance(n);
  }
}

void VolumeBuilder::flushSlab() {
  const std::size_t row = std::size_t(dims_.x);
  auto acc = grid_->getAccessor();
  for (std::size_t r = 0; r * row < inSlab_; ++r) {
    const float* v = slab_.data() + r * row;
    const int j = int(r % std::size_t(dims_.y)), k = slabZ_ + int(r / std::size_t(dims_.y));
    bool finite = true, material = false;
    for (std::size_t i = 0; i < row; ++i)  // no early exit: it vectorises
      finite &= std::isfinite(v[i]), material |= v[i] > airValue_;
    if (!finite)
      for (std::size_t i = 0; i < row; ++i)
        if (!std::isfinite(v[i])) refuseNonFiniteDensity(source_, v[i], int(i), j, k);
    if (!material) continue;
    for (std::size_t i = 0; i < row; ++i)
      if (v[i] > airValue_) acc.setValue(openvdb::Coord(int(i), j, k), v[i]);
  }
  slabZ_ += int(inSlab_ / (row * std::size_t(dims_.y)));
  inSlab_ = 0;
}

VoxelVolume VolumeBuilder::finish() {
  if (done_ != total_)
    throw VolumeError(source_ + ": " + std::to_string(done_) + " of its " + std::to_string(total_) +
                      " voxels were given a density");
  if (inSlab_ > 0) flushSlab();
  return VoxelVolume(std::move(grid_), dims_, voxelSize_, airValue_);
}

}  // namespace millsim
