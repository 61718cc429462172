#pragma once
// VoxelVolume: the density values of one CT-like volume on an OpenVDB grid, in
// index space (voxel (i, j, k) is grid coordinate (i, j, k); i is the file's
// fastest axis), plus the voxel size and the X3D VolumeData placement: the
// volume is centred on its local origin, voxel (i, j, k) at
// ((i − (nx−1)/2)·sx, (j − (ny−1)/2)·sy, (k − (nz−1)/2)·sz).
//
// Air is the grid background, so empty space costs nothing (sparse). Material
// is kept in leaf nodes, never in constant tiles, so that milling only changes
// values and never allocates.
#include <cstdint>
#include <string>

#include <glm/vec3.hpp>
#include <openvdb/openvdb.h>

#include "millsim/volume/VolumeError.h"
#include "millsim/volume/VoxelSizeRange.h"

namespace millsim {

class VoxelVolume {
public:
  using Grid = openvdb::FloatGrid;

  VoxelVolume(Grid::Ptr grid, glm::ivec3 dims, glm::dvec3 voxelSize, float airValue);
  // Out of line, as are the members below that walk the tree: inlined, they
  // make every including file instantiate and optimise OpenVDB's tree code
  // (about 10 s of a release build per file).
  ~VoxelVolume();
  VoxelVolume(const VoxelVolume&);
  VoxelVolume(VoxelVolume&&) noexcept;
  VoxelVolume& operator=(const VoxelVolume&);
  VoxelVolume& operator=(VoxelVolume&&) noexcept;

  // Copies a dense block (x fastest, then y, then z). Values at or below
  // airValue become background. Throws VolumeError on bad sizes or spacing,
  // or on a density that is not finite; `source` (a file) names it there.
  static VoxelVolume fromDense(const float* values, glm::ivec3 dims, glm::dvec3 voxelSize, float airValue,
                               const std::string& source = "volume");

  const glm::ivec3& dims() const { return dims_; }
  const glm::dvec3& voxelSize() const { return voxelSize_; }
  float airValue() const { return airValue_; }
  Grid& grid() { return *grid_; }
  const Grid& grid() const { return *grid_; }
  Grid::Ptr gridPtr() const { return grid_; }

  glm::dvec3 localToIndex(const glm::dvec3& p) const { return p / voxelSize_ + halfExtent_; }
  glm::dvec3 indexToLocal(const glm::dvec3& ijk) const { return (ijk - halfExtent_) * voxelSize_; }
  // Half of the volume's size in local coordinates (m), from centre to outer voxel faces.
  glm::dvec3 halfSize() const { return glm::dvec3(dims_) * voxelSize_ * 0.5; }
  bool insideIndexBounds(const openvdb::Coord& c) const {
    return c.x() >= 0 && c.y() >= 0 && c.z() >= 0 && c.x() < dims_.x && c.y() < dims_.y && c.z() < dims_.z;
  }

  std::size_t memoryBytes() const;
  std::uint64_t activeVoxels() const;
  float valueAt(int i, int j, int k) const;

  // Deterministic digest of dimensions, spacing and every voxel value (FNV-1a over a dense walk).
  std::uint64_t contentHash() const;

  // The stored densities (those above air): how many, their range, their
  // 10th, 50th and 90th percentiles (to 1/4096 of the range), and how many
  // lie above `iso`. What a scene author reads to choose isoValue and Tissue
  // ranges (`millsim check`).
  struct DensitySummary {
    std::uint64_t voxels = 0, aboveIso = 0;
    float min = 0.f, max = 0.f, p10 = 0.f, p50 = 0.f, p90 = 0.f;
  };
  DensitySummary densitySummary(float iso) const;

private:
  Grid::Ptr grid_;
  glm::ivec3 dims_;
  glm::dvec3 voxelSize_;
  glm::dvec3 halfExtent_;  // (dims − 1) / 2, in voxels
  float airValue_;
};

// Refuses dimensions that are not positive or would not fit in memory, and
// spacing that is not positive and finite or outside [kMinVoxelSize,
// kMaxVoxelSize]. `what` names the source in the message.
void checkVolumeShape(const std::string& what, glm::ivec3 dims, glm::dvec3 voxelSize);

// Throws the VolumeError for voxel (i, j, k) of `what` holding a density that
// is not finite. A NaN compares false with air, so it would stay material and
// turn every field sample near it into NaN: readers refuse it where it is read.
[[noreturn]] void refuseNonFiniteDensity(const std::string& what, float value, int i, int j, int k);

// Largest volume accepted, in voxels (4 GiB of floats).
inline constexpr std::uint64_t kMaxVoxels = std::uint64_t(1) << 30;

}  // namespace millsim
