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
  if (tissues_) {
    const glm::ivec3 v(glm::round(index));
    if (const int label = tissues_->labelAt(v.x, v.y, v.z); label > 0)
      return tissues_->entries()[std::size_t(label)].colour;
  }
  return densityColour(sampler.density(index), iso);
}

void VolumeMesh::upload(const IsoSurfaceMesher::ChunkKey& key, const MeshChunk& chunk) {
  // The tissue is read two voxels below the surface: on the surface itself
  // every sample equals the iso-value.
  const VolumeSampler sampler(voxels_);
  const double depth = 2.0 * std::min({voxels_.voxelSize().x, voxels_.voxelSize().y, voxels_.voxelSize().z});
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
