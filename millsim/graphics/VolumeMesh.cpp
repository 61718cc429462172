#include "millsim/graphics/VolumeMesh.h"

#include <algorithm>

#include <glm/common.hpp>

#include "millsim/graphics/CoarseVolume.h"
#include "millsim/volume/TissueMap.h"
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
  const glm::ivec3 fine = voxels.dims(), coarse = coarseDims(fine, 2);
  levels_[1].own = std::make_unique<VoxelVolume>(VoxelVolume::Grid::create(voxels.airValue()), coarse,
                                                 2.0 * voxels.voxelSize(), voxels.airValue());
  levels_[1].mesher = std::make_unique<IsoSurfaceMesher>(*levels_[1].own, isoValue);
  // Coarse voxel i averages fine voxels 2i and 2i + 1, centred at fine index 2i + ½.
  coarseOffset_ = (glm::dvec3(coarse) - 0.5 * glm::dvec3(fine)) * voxels.voxelSize();
}

double VolumeMesh::voxelSize() const {
  const glm::dvec3 h = voxels_.voxelSize();
  return std::min({h.x, h.y, h.z});
}

void VolumeMesh::build() {
  levels_[1].own->grid().clear();
  averageAll(voxels_, *levels_[1].own, 2);
  for (int l = 0; l < 2; ++l) {
    Level& level = levels_[l];
    level.mesher->buildAll();
    level.gpu.clear();
    for (const auto& [key, chunk] : level.mesher->chunks()) upload(level, key, chunk, l ? coarseOffset_ : glm::dvec3(0.0));
  }
}

void VolumeMesh::update(const std::vector<BlockOrigin>& blocks) {
  if (blocks.empty()) return;
  // Level 1: re-average what the changed blocks cover, and re-mesh its blocks there.
  std::vector<BlockOrigin> coarseBlocks;
  for (const BlockOrigin& o : blocks) {
    averageBlocks(voxels_, *levels_[1].own, 2, o / 2, o / 2 + glm::ivec3(DirtyBlocks::kSize / 2 - 1));
    const BlockOrigin c = (o / 2) / DirtyBlocks::kSize * DirtyBlocks::kSize;
    if (std::find(coarseBlocks.begin(), coarseBlocks.end(), c) == coarseBlocks.end()) coarseBlocks.push_back(c);
  }
  for (int l = 0; l < 2; ++l) {
    Level& level = levels_[l];
    for (const auto& key : level.mesher->update(l ? coarseBlocks : blocks)) {
      if (const MeshChunk* c = level.mesher->chunk(key))
        upload(level, key, *c, l ? coarseOffset_ : glm::dvec3(0.0));
      else
        level.gpu.erase(key);  // the chunk no longer holds any surface
    }
  }
}

void VolumeMesh::draw(int level) const {
  for (const auto& [key, mesh] : levels_[level == 0 ? 0 : 1].gpu) mesh.draw();
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
