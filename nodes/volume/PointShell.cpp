#include "millsim/volume/PointShell.h"

#include <glm/geometric.hpp>

namespace millsim {

PointShell::PointShell(const VoxelVolume& volume, float isoValue, int scale)
    : volume_(&volume), iso_(isoValue), scale_(scale) {
  if (scale < 1) throw VolumeError("point shell scale must be a positive integer, got " + std::to_string(scale));
  coarseDims_ = (volume.dims() + scale - 1) / scale;
  bucketDims_ = (coarseDims_ + kBucket - 1) / kBucket;
  superDims_ = (bucketDims_ + kSuper - 1) / kSuper;
  buckets_.resize(std::size_t(bucketDims_.x) * bucketDims_.y * bucketDims_.z);
  supers_.resize(std::size_t(superDims_.x) * superDims_.y * superDims_.z);
  for (int bz = 0; bz < bucketDims_.z; ++bz)
    for (int by = 0; by < bucketDims_.y; ++by)
      for (int bx = 0; bx < bucketDims_.x; ++bx) {
        const int s = ((bz / kSuper) * superDims_.y + by / kSuper) * superDims_.x + bx / kSuper;
        supers_[std::size_t(s)].buckets.push_back((bz * bucketDims_.y + by) * bucketDims_.x + bx);
      }

  // Reserve room for every surface point a bucket could ever hold if it holds
  // material now: milling only removes material, so no other bucket can gain points.
  auto acc = volume.grid().getConstAccessor();
  const int bucketVoxels = kBucket * kBucket * kBucket;
  for (auto leaf = volume.grid().tree().cbeginLeaf(); leaf; ++leaf) {
    if (leaf->onVoxelCount() == 0) continue;
    const openvdb::Coord o = leaf->origin();
    // A fine leaf can reach into two coarse buckets per axis at most.
    for (int dz = 0; dz < 2; ++dz)
      for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) {
          const glm::ivec3 b = glm::ivec3(o.x() + dx * 7, o.y() + dy * 7, o.z() + dz * 7) / scale / kBucket;
          if (glm::any(glm::greaterThanEqual(b, bucketDims_))) continue;
          auto& pts = buckets_[std::size_t((b.z * bucketDims_.y + b.y) * bucketDims_.x + b.x)].points;
          if (pts.capacity() == 0) pts.reserve(std::size_t(bucketVoxels));
        }
  }
  for (int b = 0; b < int(buckets_.size()); ++b) rebuildBucket(acc, b);
  for (int s = 0; s < int(supers_.size()); ++s) refreshSuper(s);
}

// Mean density of the coarse voxel (I, J, K): the s³ fine voxels it covers.
float PointShell::coarse(const VoxelVolume::Grid::ConstAccessor& acc, int I, int J, int K) const {
  if (scale_ == 1) return acc.getValue(openvdb::Coord(I, J, K));
  if (I < 0 || J < 0 || K < 0 || I >= coarseDims_.x || J >= coarseDims_.y || K >= coarseDims_.z)
    return volume_->airValue();
  double sum = 0.0;
  for (int k = 0; k < scale_; ++k)
    for (int j = 0; j < scale_; ++j)
      for (int i = 0; i < scale_; ++i)
        sum += acc.getValue(openvdb::Coord(I * scale_ + i, J * scale_ + j, K * scale_ + k));
  return static_cast<float>(sum / double(scale_ * scale_ * scale_));
}

void PointShell::rebuildBucket(const VoxelVolume::Grid::ConstAccessor& acc, int b) {
  Bucket& bucket = buckets_[std::size_t(b)];
  count_ -= bucket.points.size();
  bucket.points.clear();
  bucket.box = Aabb{};
  if (bucket.points.capacity() == 0) return;  // never held material
  const int bx = b % bucketDims_.x, by = (b / bucketDims_.x) % bucketDims_.y, bz = b / (bucketDims_.x * bucketDims_.y);
  const glm::ivec3 lo = glm::ivec3(bx, by, bz) * kBucket;
  const glm::ivec3 hi = glm::min(lo + kBucket, coarseDims_);
  // Coarse voxel centre in fine index units, and the coarse spacing in fine units.
  const double offset = 0.5 * (scale_ - 1);
  for (int K = lo.z; K < hi.z; ++K)
    for (int J = lo.y; J < hi.y; ++J)
      for (int I = lo.x; I < hi.x; ++I) {
        const float v = coarse(acc, I, J, K);
        if (v <= iso_) continue;
        const float n[6] = {coarse(acc, I - 1, J, K), coarse(acc, I + 1, J, K), coarse(acc, I, J - 1, K),
                            coarse(acc, I, J + 1, K), coarse(acc, I, J, K - 1), coarse(acc, I, J, K + 1)};
        bool surface = false;
        for (float x : n) surface |= x <= iso_;
        if (!surface) continue;
        // Outward normal: down the density gradient (central differences; the
        // voxel size makes it a gradient in metres for anisotropic volumes).
        const glm::dvec3 h = volume_->voxelSize() * double(scale_);
        glm::dvec3 g((n[1] - n[0]) / h.x, (n[3] - n[2]) / h.y, (n[5] - n[4]) / h.z);
        double len = glm::length(g);
        if (!(len > 0.0)) {
          // Symmetric neighbourhood (a one-voxel spike): point towards the outside neighbours.
          g = glm::dvec3(double(n[0] <= iso_) - double(n[1] <= iso_), double(n[2] <= iso_) - double(n[3] <= iso_),
                         double(n[4] <= iso_) - double(n[5] <= iso_));
          len = glm::length(g);
          if (!(len > 0.0)) g = glm::dvec3(0, -1, 0), len = 1.0;
        }
        const glm::dvec3 fine = glm::dvec3(I, J, K) * double(scale_) + offset;
        ShellPoint p{glm::vec3(volume_->indexToLocal(fine)), glm::vec3(-g / len)};
        bucket.points.push_back(p);
        bucket.box.add(p.position);
      }
  count_ += bucket.points.size();
}

void PointShell::refreshSuper(int s) {
  Super& sup = supers_[std::size_t(s)];
  sup.box = Aabb{};
  sup.count = 0;
  for (int b : sup.buckets) {
    sup.box.add(buckets_[std::size_t(b)].box);
    sup.count += buckets_[std::size_t(b)].points.size();
  }
}

int PointShell::update(const VoxelVolume& volume, const std::vector<openvdb::Coord>& dirty) {
  if (dirty.empty()) return 0;
  auto acc = volume.grid().getConstAccessor();
  // A changed voxel changes its coarse voxel and, through the neighbour test and
  // the normals, coarse voxels one step away: widen each block by one coarse voxel.
  int rebuilt = 0;
  // Small fixed-size marks avoid rebuilding a bucket twice without allocating.
  constexpr int kMaxMarked = 256;
  int marked[kMaxMarked];
  int nMarked = 0;
  auto rebuildOnce = [&](int b) {
    for (int i = 0; i < nMarked; ++i)
      if (marked[i] == b) return;
    if (nMarked < kMaxMarked) marked[nMarked++] = b;
    rebuildBucket(acc, b);
    ++rebuilt;
  };
  for (const openvdb::Coord& o : dirty) {
    const glm::ivec3 cLo = glm::max(glm::ivec3(o.x(), o.y(), o.z()) / scale_ - 1, glm::ivec3(0));
    const glm::ivec3 cHi = glm::min((glm::ivec3(o.x(), o.y(), o.z()) + 7) / scale_ + 1, coarseDims_ - 1);
    const glm::ivec3 bLo = cLo / kBucket, bHi = cHi / kBucket;
    for (int bz = bLo.z; bz <= bHi.z; ++bz)
      for (int by = bLo.y; by <= bHi.y; ++by)
        for (int bx = bLo.x; bx <= bHi.x; ++bx) rebuildOnce((bz * bucketDims_.y + by) * bucketDims_.x + bx);
  }
  // Refresh the super-buckets of everything rebuilt.
  for (int i = 0; i < nMarked; ++i) {
    const int b = marked[i];
    const int bx = b % bucketDims_.x, by = (b / bucketDims_.x) % bucketDims_.y, bz = b / (bucketDims_.x * bucketDims_.y);
    refreshSuper(((bz / kSuper) * superDims_.y + by / kSuper) * superDims_.x + bx / kSuper);
  }
  if (nMarked == kMaxMarked)  // more than we could track: refresh all super-buckets
    for (int s = 0; s < int(supers_.size()); ++s) refreshSuper(s);
  return rebuilt;
}

std::vector<ShellPoint> PointShell::points() const {
  std::vector<ShellPoint> out;
  out.reserve(count_);
  forEach([&](const ShellPoint& p) { out.push_back(p); });
  return out;
}

std::size_t PointShell::memoryBytes() const {
  std::size_t bytes = buckets_.capacity() * sizeof(Bucket) + supers_.capacity() * sizeof(Super);
  for (const auto& b : buckets_) bytes += b.points.capacity() * sizeof(ShellPoint);
  for (const auto& s : supers_) bytes += s.buckets.capacity() * sizeof(int);
  return bytes;
}

}  // namespace millsim
