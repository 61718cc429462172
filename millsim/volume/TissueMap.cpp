#include "millsim/volume/TissueMap.h"

#include <algorithm>
#include <cmath>

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
  // stays background. Walked serially (a few ms for a tooth), so the result
  // and the counts do not depend on threads.
  map->labels_ = LabelGrid::create(0);
  map->labels_->setTree(std::make_shared<LabelGrid::TreeType>(volume.grid().tree(), 0, openvdb::TopologyCopy()));
  const VoxelVolume::Grid::TreeType& density = volume.grid().tree();
  auto labelAcc = labelVolume ? std::make_unique<VoxelVolume::Grid::ConstAccessor>(labelVolume->grid().getConstAccessor())
                              : nullptr;
  for (auto leaf = map->labels_->tree().beginLeaf(); leaf; ++leaf) {
    const auto* densityLeaf = density.probeConstLeaf(leaf->origin());
    for (auto v = leaf->beginValueOn(); v; ++v) {
      const float d = densityLeaf ? densityLeaf->getValue(v.pos()) : density.getValue(v.getCoord());
      const float l = labelAcc ? labelAcc->getValue(v.getCoord()) : -1.f;
      int entry = 0;
      for (std::size_t t = 0; t < tissues.size() && entry == 0; ++t) {
        const Tissue& ts = *tissues[t];
        const glm::vec2 r = ts.densityRange.get();
        const bool match = ts.byDensity() ? (d >= r.x && d < r.y) : labelOf[t] >= 0 && std::lround(l) == labelOf[t];
        if (match) entry = int(t) + 1;
      }
      v.setValue(entry);
      ++map->counts_[std::size_t(entry)];
      if (d < isoValue) {
        ++map->below_[std::size_t(entry)];
        belowSum[std::size_t(entry)] += d;
      }
    }
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
