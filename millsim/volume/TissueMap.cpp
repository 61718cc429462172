#include "millsim/volume/TissueMap.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <tbb/parallel_for.h>

#include "millsim/volume/Tissue.h"

namespace millsim {

std::unique_ptr<TissueMap> TissueMap::build(const VoxelVolume& volume, const std::vector<const Tissue*>& tissues,
                                            const VoxelVolume* labelVolume, float isoValue,
                                            const std::vector<std::string>& parts) {
  auto map = std::make_unique<TissueMap>();
  map->entries_.push_back(Entry{"(unclassified material)", 1.f, glm::vec3(0.85f, 0.8f, 0.7f)});
  bool needLabels = false;
  // Each tissue's label: its own, or its part's (by name); -1 by density.
  std::vector<long> labelOf;
  for (const Tissue* t : tissues) {
    map->entries_.push_back(Entry{t->name.get(), t->hardness.get(), t->color.get().rgb, t->soft.get()});
    needLabels |= !t->byDensity();
    long label = t->byDensity() ? -1 : t->label.get();
    if (t->byPartName()) {
      const auto it = std::find(parts.begin(), parts.end(), t->name.get());
      if (it == parts.end()) {
        std::string known;
        for (const std::string& p : parts) known += (known.empty() ? "" : ", ") + ("'" + p + "'");
        throw VolumeError("Tissue '" + t->name.get() + "' has neither densityRange nor label, and " +
                          (parts.empty() ? std::string("the volume is not a mesh with parts to choose by name; give one")
                                         : "the mesh has no part of that name (its parts: " + known + ")"));
      }
      label = long(it - parts.begin()) + 1;
    }
    labelOf.push_back(label);
  }
  if (needLabels && !labelVolume)
    throw VolumeError("a Tissue is chosen by label, but the VolumeObject has no labelUrl volume");
  if (labelVolume && labelVolume->dims() != volume.dims()) {
    const auto text = [](glm::ivec3 d) {
      return std::to_string(d.x) + "x" + std::to_string(d.y) + "x" + std::to_string(d.z);
    };
    throw VolumeError("the label volume is " + text(labelVolume->dims()) + " voxels, the density volume " +
                      text(volume.dims()) + "; they must match voxel for voxel");
  }
  for (const Entry& e : map->entries_) map->hardness_.push_back(e.hardness);
  map->counts_.assign(map->entries_.size(), 0);
  map->below_.assign(map->entries_.size(), 0);
  std::vector<double> belowSum(map->entries_.size(), 0.0);

  // Same topology as the densities: every material voxel gets a label, air
  // stays background. Leaves on TBB's threads (serially the walk was 1 s of a
  // 25 µm lesson's opening), each chunk of kChunk leaves summed apart and the
  // chunks added in order: the counts and sums do not depend on the split.
  map->labels_ = LabelGrid::create(0);
  map->labels_->setTree(std::make_shared<LabelGrid::TreeType>(volume.grid().tree(), 0, openvdb::TopologyCopy()));
  const VoxelVolume::Grid::TreeType& density = volume.grid().tree();
  const VoxelVolume::Grid::TreeType* labelTree = labelVolume ? &labelVolume->grid().tree() : nullptr;
  std::vector<LabelGrid::TreeType::LeafNodeType*> leaves;
  map->labels_->tree().getNodes(leaves);
  const std::size_t nEntries = map->entries_.size();
  struct Sums {
    std::vector<std::uint64_t> counts, below;
    std::vector<double> belowSum;
  };
  constexpr std::size_t kChunk = 64;
  std::vector<Sums> chunks((leaves.size() + kChunk - 1) / kChunk);
  tbb::parallel_for(std::size_t(0), chunks.size(), [&](std::size_t c) {
    Sums& sums = chunks[c];
    sums.counts.assign(nEntries, 0), sums.below.assign(nEntries, 0), sums.belowSum.assign(nEntries, 0.0);
    for (std::size_t i = c * kChunk; i < std::min(leaves.size(), (c + 1) * kChunk); ++i) {
      auto& leaf = *leaves[i];
      const auto* densityLeaf = density.probeConstLeaf(leaf.origin());
      const auto* labelLeaf = labelTree ? labelTree->probeConstLeaf(leaf.origin()) : nullptr;
      for (auto v = leaf.beginValueOn(); v; ++v) {
        const float d = densityLeaf ? densityLeaf->getValue(v.pos()) : density.getValue(v.getCoord());
        const float l = !labelTree ? -1.f : labelLeaf ? labelLeaf->getValue(v.pos()) : labelTree->getValue(v.getCoord());
        int entry = 0;
        for (std::size_t t = 0; t < tissues.size() && entry == 0; ++t) {
          const Tissue& ts = *tissues[t];
          const glm::vec2 r = ts.densityRange.get();
          const bool match = ts.byDensity() ? (d >= r.x && d < r.y) : labelOf[t] >= 0 && std::lround(l) == labelOf[t];
          if (match) entry = int(t) + 1;
        }
        v.setValue(entry);
        ++sums.counts[std::size_t(entry)];
        if (d < isoValue) {
          ++sums.below[std::size_t(entry)];
          sums.belowSum[std::size_t(entry)] += d;
        }
      }
    }
  });
  for (const Sums& sums : chunks)
    for (std::size_t e = 0; e < nEntries; ++e) {
      map->counts_[e] += sums.counts[e], map->below_[e] += sums.below[e];
      belowSum[e] += sums.belowSum[e];
    }
  for (std::size_t e = 0; e < map->entries_.size(); ++e)
    map->entries_[e].densityBelowSurface =
        map->below_[e] > 0 ? float(belowSum[e] / double(map->below_[e])) : std::numeric_limits<float>::quiet_NaN();
  for (std::size_t e = 1; e < map->entries_.size(); ++e)
    map->entries_[e].soft |= map->counts_[e] > 0 && 2 * map->below_[e] > map->counts_[e];
  // Whole leaves of one tissue (the inside of the dentin) become tiles.
  map->labels_->tree().prune();
  return map;
}

int TissueMap::find(const std::string& name) const {
  for (std::size_t i = 1; i < entries_.size(); ++i)
    if (entries_[i].name == name) return int(i);
  return 0;
}

}  // namespace millsim
