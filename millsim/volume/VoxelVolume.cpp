#include "millsim/volume/VoxelVolume.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include <tbb/parallel_for.h>

#include "millsim/volume/VolumeBuilder.h"

namespace millsim {

// The last owner frees the grid's nodes itself, serially: OpenVDB's own
// Tree::clear() (its destructor's) first gathers the nodes into a vector, and
// when memory has run out that allocation throws inside the destructor and
// the process aborts (a 25 µm lesson under a 700 MB cap did, unwinding from
// the first std::bad_alloc). RootNode::clear() deletes the nodes without
// allocating; the tree it leaves is empty, so its destructor allocates nothing.
VoxelVolume::~VoxelVolume() {
  if (grid_ && grid_.use_count() == 1) grid_->tree().root().clear();
}
VoxelVolume::VoxelVolume(const VoxelVolume&) = default;
VoxelVolume::VoxelVolume(VoxelVolume&&) noexcept = default;
VoxelVolume& VoxelVolume::operator=(const VoxelVolume&) = default;
VoxelVolume& VoxelVolume::operator=(VoxelVolume&&) noexcept = default;

std::size_t VoxelVolume::memoryBytes() const { return static_cast<std::size_t>(grid_->memUsage()); }
std::uint64_t VoxelVolume::activeVoxels() const { return grid_->activeVoxelCount(); }
float VoxelVolume::valueAt(int i, int j, int k) const { return grid_->tree().getValue(openvdb::Coord(i, j, k)); }

VoxelVolume::VoxelVolume(Grid::Ptr grid, glm::ivec3 dims, glm::dvec3 voxelSize, float airValue)
    : grid_(std::move(grid)),
      dims_(dims),
      voxelSize_(voxelSize),
      halfExtent_((glm::dvec3(dims) - 1.0) * 0.5),
      airValue_(airValue) {
  checkVolumeShape("volume", dims, voxelSize);
  // Milling writes voxels in place: material must live in leaves, not tiles.
  grid_->tree().voxelizeActiveTiles();
}

void refuseNonFiniteDensity(const std::string& what, float value, int i, int j, int k) {
  std::ostringstream m;
  m << what << ": voxel (" << i << ", " << j << ", " << k << ") has the density " << value
    << "; a density must be a finite number";
  throw VolumeError(m.str());
}

void checkVolumeShape(const std::string& what, glm::ivec3 dims, glm::dvec3 voxelSize) {
  if (dims.x <= 0 || dims.y <= 0 || dims.z <= 0)
    throw VolumeError(what + ": dimensions " + std::to_string(dims.x) + "x" + std::to_string(dims.y) + "x" +
                      std::to_string(dims.z) + " are not all positive");
  const std::uint64_t n = std::uint64_t(dims.x) * std::uint64_t(dims.y) * std::uint64_t(dims.z);
  if (n > kMaxVoxels)
    throw VolumeError(what + ": dimensions " + std::to_string(dims.x) + "x" + std::to_string(dims.y) + "x" +
                      std::to_string(dims.z) + " (" + std::to_string(n) + " voxels) exceed the limit of " +
                      std::to_string(kMaxVoxels) + " voxels");
  for (int a = 0; a < 3; ++a)
    if (!std::isfinite(voxelSize[a]) || voxelSize[a] <= 0.0)
      throw VolumeError(what + ": voxel size " + std::to_string(voxelSize[a]) + " along axis " + "xyz"[a] +
                        " is not a positive finite number of metres");
  for (int a = 0; a < 3; ++a)
    if (voxelSize[a] < kMinVoxelSize || voxelSize[a] > kMaxVoxelSize) {
      std::ostringstream m;
      m << what << ": voxel size " << voxelSize[a] << " m (" << voxelSize[a] * 1e3 << " mm) along axis " << "xyz"[a]
        << " is outside " << kMinVoxelSize << " to " << kMaxVoxelSize << " m (" << kMinVoxelSize * 1e3 << " to "
        << kMaxVoxelSize * 1e3 << " mm)";
      if (voxelSize[a] < kMinVoxelSize)
        m << "; volume files give spacings in millimetres: was it written in metres?";
      throw VolumeError(m.str());
    }
}

VoxelVolume VoxelVolume::fromDense(const float* values, glm::ivec3 dims, glm::dvec3 voxelSize, float airValue,
                                   const std::string& source) {
  VolumeBuilder builder(dims, voxelSize, airValue, source);
  builder.append(values, builder.valuesTotal());
  return builder.finish();
}

// Both passes leaf by leaf on TBB's threads (a 25 µm tooth is 50 M voxels:
// half a second serially), each chunk of leaves summed apart; every figure is
// a count, a minimum or a maximum, so the result does not depend on the split.
// Every active value is a leaf's: the constructor voxelises active tiles.
VoxelVolume::DensitySummary VoxelVolume::densitySummary(float iso) const {
  std::vector<const Grid::TreeType::LeafNodeType*> leaves;
  grid_->tree().getNodes(leaves);
  constexpr std::size_t kChunk = 256;
  const std::size_t nChunks = (leaves.size() + kChunk - 1) / kChunk;
  auto forChunks = [&](auto&& visit) {  // visit(chunk, value) for each active value of the chunk's leaves
    tbb::parallel_for(std::size_t(0), nChunks, [&](std::size_t c) {
      for (std::size_t i = c * kChunk; i < std::min(leaves.size(), (c + 1) * kChunk); ++i)
        for (auto v = leaves[i]->cbeginValueOn(); v; ++v) visit(c, *v);
    });
  };
  std::vector<DensitySummary> parts(nChunks);
  forChunks([&](std::size_t c, float v) {
    DensitySummary& p = parts[c];
    p.min = p.voxels == 0 ? v : std::min(p.min, v), p.max = p.voxels == 0 ? v : std::max(p.max, v);
    ++p.voxels, p.aboveIso += v > iso;
  });
  DensitySummary s;
  for (const DensitySummary& p : parts) {
    if (p.voxels == 0) continue;
    s.min = s.voxels == 0 ? p.min : std::min(s.min, p.min), s.max = s.voxels == 0 ? p.max : std::max(s.max, p.max);
    s.voxels += p.voxels, s.aboveIso += p.aboveIso;
  }
  if (s.voxels == 0) return s;
  // Percentiles from a histogram of the range: two passes, no copy of the voxels.
  constexpr int kBins = 4096;
  const double width = (double(s.max) - double(s.min)) / kBins;
  auto bin = [&](float v) { return width > 0.0 ? std::min(kBins - 1, int((double(v) - s.min) / width)) : 0; };
  std::vector<std::vector<std::uint64_t>> chunkBins(nChunks);
  forChunks([&](std::size_t c, float v) {
    if (chunkBins[c].empty()) chunkBins[c].assign(kBins, 0);
    ++chunkBins[c][std::size_t(bin(v))];
  });
  std::vector<std::uint64_t> bins(kBins, 0);
  for (const auto& b : chunkBins)
    for (std::size_t i = 0; i < b.size(); ++i) bins[i] += b[i];
  auto percentile = [&](double fraction) {
    const double want = fraction * double(s.voxels);
    std::uint64_t seen = 0;
    for (int b = 0; b < kBins; ++b)
      if (double(seen += bins[std::size_t(b)]) >= want) return float(s.min + (b + 0.5) * width);
    return s.max;
  };
  s.p10 = percentile(0.1), s.p50 = percentile(0.5), s.p90 = percentile(0.9);
  return s;
}

std::uint64_t VoxelVolume::contentHash() const {
  std::uint64_t h = 1469598103934665603ull;
  auto mix = [&h](const void* p, std::size_t n) {
    const auto* b = static_cast<const unsigned char*>(p);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
  };
  mix(&dims_, sizeof dims_);
  mix(&voxelSize_, sizeof voxelSize_);
  auto acc = grid_->getConstAccessor();
  for (int k = 0; k < dims_.z; ++k)
    for (int j = 0; j < dims_.y; ++j)
      for (int i = 0; i < dims_.x; ++i) {
        float v = acc.getValue(openvdb::Coord(i, j, k));
        if (!acc.isValueOn(openvdb::Coord(i, j, k))) v = airValue_;
        mix(&v, sizeof v);
      }
  return h;
}

}  // namespace millsim
