#include "millsim/graphics/VolumeMesh.h"

#include <algorithm>

#include <glm/common.hpp>

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
    : voxels_(voxels), tissues_(tissues), mesher_(voxels, isoValue) {}

void VolumeMesh::build() {
  mesher_.buildAll();
  gpu_.clear();
  for (const auto& [key, chunk] : mesher_.chunks()) upload(key, chunk);
}

void VolumeMesh::update(const std::vector<BlockOrigin>& blocks) {
  for (const auto& key : mesher_.update(blocks)) {
    if (const MeshChunk* c = mesher_.chunk(key))
      upload(key, *c);
    else
      gpu_.erase(key);  // the chunk no longer holds any surface
  }
}

void VolumeMesh::draw() const {
  for (const auto& [key, mesh] : gpu_) mesh.draw();
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

void VolumeMesh::upload(const IsoSurfaceMesher::ChunkKey& key, const MeshChunk& chunk) {
  // The density is read two voxels below the surface (on the surface itself
  // every sample equals the iso-value); tissue labels half a voxel below it,
  // where the outermost layer is.
  const VolumeSampler sampler(voxels_);
  const double voxel = std::min({voxels_.voxelSize().x, voxels_.voxelSize().y, voxels_.voxelSize().z});
  const double depth = (tissues_ ? 0.5 : 2.0) * voxel;
  const float iso = mesher_.isoValue();
  scratch_.resize(chunk.positions.size());
  for (std::size_t i = 0; i < chunk.positions.size(); ++i) {
    const glm::dvec3 inside = glm::dvec3(chunk.positions[i]) - depth * glm::dvec3(chunk.normals[i]);
    scratch_[i] = {chunk.positions[i], chunk.normals[i], colourAt(sampler, voxels_.localToIndex(inside), iso)};
  }
  gpu_[key].upload(scratch_, chunk.indices);
  ++uploads_;
}

}  // namespace millsim
