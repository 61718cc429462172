#include "millsim/graphics/VolumeMesh.h"

#include <algorithm>

#include <glm/common.hpp>

#include "millsim/graphics/CoarseVolume.h"
#include "millsim/volume/TissueMap.h"
#include "millsim/volume/VoxelSizeRange.h"
#include "millsim/volume/VolumeSampler.h"

namespace millsim {

glm::vec3 densityColour(float d, float iso) {
  const glm::vec3 soft(0.80f, 0.60f, 0.50f), dentin(0.92f, 0.76f, 0.46f), enamel(0.90f, 0.93f, 0.97f);
  constexpr float kDentin = 1600.f, kEnamel = 2800.f;
  if (d >= kDentin) return glm::mix(dentin, enamel, std::clamp((d - kDentin) / (kEnamel - kDentin), 0.f, 1.f));
  const float lo = std::min(iso, kDentin - 1.f);
  return glm::mix(soft, dentin, std::clamp((d - lo) / (kDentin - lo), 0.f, 1.f));
}

VolumeMesh::VolumeMesh(const VoxelVolume& voxels, float isoValue, const TissueMap* tissues)
    : voxels_(voxels), tissues_(tissues), iso_(isoValue) {
  levels_[0].mesher = std::make_unique<IsoSurfaceMesher>(voxels, isoValue);
  const glm::ivec3 fine = voxels.dims();
  const glm::dvec3 h = voxels.voxelSize();
  // As many levels as a volume's voxels may grow to (VoxelSizeRange.h): a
  // clinical CT of 2 mm voxels has levels 0 to 2.
  while (levelCount_ < kLevels && double(1 << levelCount_) * std::max({h.x, h.y, h.z}) <= kMaxVoxelSize) ++levelCount_;
  levelCount_ = std::max(levelCount_, 1);
  for (int l = 1; l < levelCount_; ++l) {
    Level& level = levels_[l];
    level.factor = 1 << l;
    const glm::ivec3 coarse = coarseDims(fine, level.factor);
    level.own = std::make_unique<VoxelVolume>(VoxelVolume::Grid::create(voxels.airValue()), coarse,
                                              double(level.factor) * voxels.voxelSize(), voxels.airValue());
    level.mesher = std::make_unique<IsoSurfaceMesher>(*level.own, isoValue);
    // Coarse voxel i averages fine voxels f·i … f·i + f − 1, centred at fine index f·i + (f − 1)/2.
    level.offset = 0.5 * (double(level.factor) * glm::dvec3(coarse) - glm::dvec3(fine)) * voxels.voxelSize();
  }
}

double VolumeMesh::voxelSize() const {
  const glm::dvec3 h = voxels_.voxelSize();
  return std::min({h.x, h.y, h.z});
}

void VolumeMesh::make(Level& level) {
  if (level.own) {
    level.own->grid().clear();
    averageAll(voxels_, *level.own, level.factor);
  }
  level.mesher->buildAll();
  level.gpu.clear();
  for (const auto& [key, chunk] : level.mesher->chunks()) upload(level, key, chunk, level.offset);
  level.made = true;
}

void VolumeMesh::build() {
  for (Level& level : levels_)
    if (level.made) make(level);
}

void VolumeMesh::prepare(int level) {
  Level& l = levels_[std::clamp(level, 0, levelCount_ - 1)];
  if (!l.made) make(l);
}

void VolumeMesh::update(const std::vector<BlockOrigin>& blocks) {
  if (blocks.empty()) return;
  std::vector<BlockOrigin> coarseBlocks;
  for (Level& level : levels_) {
    if (!level.made) continue;  // made afresh when it is first drawn
    const int f = level.factor;
    if (level.own) {
      // Re-average what the changed blocks cover, and re-mesh its blocks there.
      coarseBlocks.clear();
      for (const BlockOrigin& o : blocks) {
        averageBlocks(voxels_, *level.own, f, o / f, (o + glm::ivec3(DirtyBlocks::kSize - 1)) / f);
        const BlockOrigin c = (o / f) / DirtyBlocks::kSize * DirtyBlocks::kSize;
        if (std::find(coarseBlocks.begin(), coarseBlocks.end(), c) == coarseBlocks.end()) coarseBlocks.push_back(c);
      }
    }
    for (const auto& key : level.mesher->update(level.own ? coarseBlocks : blocks)) {
      if (const MeshChunk* c = level.mesher->chunk(key))
        upload(level, key, *c, level.offset);
      else
        level.gpu.erase(key);  // the chunk no longer holds any surface
    }
  }
}

void VolumeMesh::draw(int level) const {
  for (const auto& [key, mesh] : levels_[std::clamp(level, 0, levelCount_ - 1)].gpu) mesh.draw();
}

std::size_t VolumeMesh::triangles(int level) const {
  const Level& l = levels_[std::clamp(level, 0, levelCount_ - 1)];
  return l.made ? l.mesher->triangleCount() : 0;
}

std::size_t VolumeMesh::chunks() const {
  std::size_t n = 0;
  for (const Level& level : levels_) n += level.gpu.size();
  return n;
}

glm::vec3 VolumeMesh::colourAt(const VolumeSampler& sampler, const glm::dvec3& index, float iso) const {
  // A tissue's colour where the volume has tissues (the labels never change,
  // so the cut surface shows what it was cut into); else by density.
  // The tissue colours of the eight voxels around the point are blended by
  // their trilinear weights (air's left out): a layer about as thin as the
  // sampling depth (the root's 0.15 mm of cementum) would otherwise flip
  // between two colours with where the surface crosses each voxel, painting
  // contour-line bands on every slope.
  if (tissues_) {
    const glm::dvec3 base = glm::floor(index), f = index - base;
    glm::vec3 sum(0.f);
    double weight = 0.0;
    for (int c = 0; c < 8; ++c) {
      const glm::ivec3 v = glm::ivec3(base) + glm::ivec3(c & 1, (c >> 1) & 1, (c >> 2) & 1);
      const double w = (c & 1 ? f.x : 1.0 - f.x) * (c & 2 ? f.y : 1.0 - f.y) * (c & 4 ? f.z : 1.0 - f.z);
      if (const int label = tissues_->labelAt(v.x, v.y, v.z); label > 0 && w > 0.0) {
        sum += float(w) * tissues_->entries()[std::size_t(label)].colour;
        weight += w;
      }
    }
    if (weight > 0.0) return sum / float(weight);
  }
  return densityColour(sampler.density(index), iso);
}

void VolumeMesh::upload(Level& level, const IsoSurfaceMesher::ChunkKey& key, const MeshChunk& chunk,
                        const glm::dvec3& shift) {
  // The density is read two voxels below the surface (on the surface itself
  // every sample equals the iso-value); tissue labels half a voxel below it,
  // where the outermost layer is.
  const VolumeSampler sampler(voxels_);
  const double voxel = voxelSize();
  const double depth = (tissues_ ? 0.5 : 2.0) * voxel;
  scratch_.resize(chunk.positions.size());
  for (std::size_t i = 0; i < chunk.positions.size(); ++i) {
    const glm::dvec3 at = glm::dvec3(chunk.positions[i]) + shift;  // level 0's local frame
    const glm::dvec3 inside = at - depth * glm::dvec3(chunk.normals[i]);
    scratch_[i] = {glm::vec3(at), chunk.normals[i], colourAt(sampler, voxels_.localToIndex(inside), iso_)};
    // A surface facing a soft tissue (the pulp chamber's wall, exposed by a
    // cut) is drawn in that tissue's colour: there is no surface of the soft
    // tissue itself, it lies below the isoValue.
    if (tissues_) {
      const glm::ivec3 out = glm::ivec3(glm::round(voxels_.localToIndex(at + voxel * glm::dvec3(chunk.normals[i]))));
      if (const int label = tissues_->labelAt(out.x, out.y, out.z); label > 0 && tissues_->soft(label))
        scratch_[i].colour = tissues_->entries()[std::size_t(label)].colour;
    }
  }
  level.gpu[key].upload(scratch_, chunk.indices);
  ++uploads_;
}

}  // namespace millsim
