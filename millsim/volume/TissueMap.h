#pragma once
// TissueMap: which tissue each voxel of a volume is, and what each tissue is
// like. Built once at load from the voxels' *original* densities or a label
// volume, so milling (which lowers densities) never turns enamel into dentin.
// Read by the Miller on the haptic thread (hardness) and by graphics (colour);
// nothing writes it after it is built.
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <openvdb/openvdb.h>

#include "millsim/volume/VoxelVolume.h"

namespace millsim {

class Tissue;

class TissueMap {
public:
  // Tissue index + 1 per voxel; 0 (the background) is the default material.
  using LabelGrid = openvdb::Int32Grid;

  struct Entry {
    std::string name;
    float hardness = 1.f;
    glm::vec3 colour{0.85f, 0.8f, 0.7f};
    // Below the surface: marked Tissue::soft, or most of its voxels below
    // the isoValue (the burr enters it, graphics draws it where exposed).
    bool soft = false;
    // The mean original density of its voxels below the isoValue (NaN when
    // none are): how much of a soft tissue's voxel milling has left, for a
    // cut plane's section, which draws soft tissue too.
    float densityBelowSurface = std::numeric_limits<float>::quiet_NaN();
  };

  // Classifies every material voxel of `volume`: the first tissue that
  // matches wins — by its densityRange on `volume`, or by its label on
  // `labels` (which must have the volume's dimensions; may be null when no
  // tissue is chosen by label). A voxel below `isoValue` counts as below the
  // surface (belowSurfaceCounts, Entry::soft). A tissue with neither a
  // densityRange nor a label is the part of its name in `parts` (a mesh's,
  // part i being label i + 1). Throws VolumeError naming the problem.
  static std::unique_ptr<TissueMap> build(const VoxelVolume& volume, const std::vector<const Tissue*>& tissues,
                                          const VoxelVolume* labels,
                                          float isoValue = -std::numeric_limits<float>::infinity(),
                                          const std::vector<std::string>& parts = {});

  const LabelGrid& labels() const { return *labels_; }
  // Entry 0 is the default material (hardness 1); tissue i is entry i + 1.
  const std::vector<Entry>& entries() const { return entries_; }
  const std::vector<float>& hardness() const { return hardness_; }
  int labelAt(int i, int j, int k) const { return labels_->tree().getValue(openvdb::Coord(i, j, k)); }
  // Index of the tissue named `name` (entry index, ≥ 1), or 0 if none is.
  int find(const std::string& name) const;
  // Voxels of each entry (material voxels only; entry 0 = unclassified material).
  const std::vector<std::uint64_t>& voxelCounts() const { return counts_; }
  // Of those, the voxels whose original density is below the isoValue.
  const std::vector<std::uint64_t>& belowSurfaceCounts() const { return below_; }
  bool soft(int entry) const { return entries_[std::size_t(entry)].soft; }

private:
  LabelGrid::Ptr labels_;
  std::vector<Entry> entries_;
  std::vector<float> hardness_;  // by entry, for the Miller's inner loop
  std::vector<std::uint64_t> counts_, below_;
};

}  // namespace millsim
