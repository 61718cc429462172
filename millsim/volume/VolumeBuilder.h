#pragma once
// VolumeBuilder: a VoxelVolume built from densities given in file order (x
// fastest, then y, then z), eight slices at a time. A reader that streams its
// file through it never holds a dense float copy of the whole volume: the
// peak is the sparse grid and one slab, where a dense copy costs 4 bytes a
// voxel of the box (a 512 × 512 × 400 CT: 420 MB, for a grid of some tens).
// The volume is VoxelVolume::fromDense's for the same values: densities at or
// below air are not stored, a density that is not finite is refused with its
// voxel.
#include <algorithm>
#include <cstddef>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "millsim/volume/VoxelVolume.h"

namespace millsim {

class VolumeBuilder {
public:
  // Checks the shape first (checkVolumeShape); `source` names the file in errors.
  VolumeBuilder(glm::ivec3 dims, glm::dvec3 voxelSize, float airValue, std::string source);
  ~VolumeBuilder();
  VolumeBuilder(const VolumeBuilder&) = delete;
  VolumeBuilder& operator=(const VolumeBuilder&) = delete;

  // Where the next values go: up to room() of them may be written at next(),
  // then advance(n) takes n of them (a full slab goes into the grid). room()
  // is 0 once every voxel has its value.
  float* next() { return slab_.data() + inSlab_; }
  std::size_t room() const { return std::min(slab_.size() - inSlab_, total_ - done_); }
  void advance(std::size_t n);
  // Copies `count` values (at most what is left).
  void append(const float* values, std::size_t count);

  std::size_t valuesTotal() const { return total_; }
  // Values a slab holds: advance() puts them into the grid at once (a reader
  // that runs ahead of the builder covers a few).
  std::size_t slabValues() const { return slab_.size(); }

  // The volume (once: the builder is spent). Throws VolumeError unless every
  // voxel has been given.
  VoxelVolume finish();

private:
  void flushSlab();

  glm::ivec3 dims_;
  glm::dvec3 voxelSize_;
  float airValue_;
  std::string source_;
  std::size_t total_, done_ = 0, inSlab_ = 0;
  int slabZ_ = 0;  // the first slice of the slab being filled
  std::vector<float> slab_;
  VoxelVolume::Grid::Ptr grid_;
};

}  // namespace millsim
