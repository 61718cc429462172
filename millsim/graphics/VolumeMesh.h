#pragma once
// VolumeMesh: the iso-surface of one voxel volume on the GPU. Meshes with
// IsoSurfaceMesher (16³-cell chunks) and keeps one GlMesh per chunk, so that
// after milling only the chunks the changed blocks touch are re-extracted and
// re-uploaded. Vertex colours come from the tissue just inside the surface
// (its Tissue colour), or without tissues from the density there, so enamel,
// dentin and whatever a cut exposes look different. Internal to
// the graphics library; every call needs the renderer's GL context current.
#include <map>
#include <vector>

#include "millsim/graphics/GlMesh.h"
#include "millsim/volume/IsoSurface.h"

namespace millsim {

class TissueMap;
class VolumeSampler;

// The colour of tissue of a given density (Hounsfield-like units): dentin
// (~1600) ivory-yellow, enamel (~2800) bluish white, softer tissue towards
// a pale brown.
glm::vec3 densityColour(float density, float isoValue);

class VolumeMesh {
public:
  // Keeps a reference to `voxels`, which must outlive this and must not be
  // written while build() or update() run.
  // `tissues` (optional, never written) colours the surface by tissue.
  VolumeMesh(const VoxelVolume& voxels, float isoValue, const TissueMap* tissues = nullptr);

  void build();                                             // everything afresh
  void update(const std::vector<BlockOrigin>& blocks);   // after these 8³ blocks changed
  void draw() const;

  std::size_t triangles() const { return mesher_.triangleCount(); }
  std::size_t chunks() const { return gpu_.size(); }
  std::size_t uploads() const { return uploads_; }  // chunk uploads since construction

private:
  void upload(const IsoSurfaceMesher::ChunkKey& key, const MeshChunk& chunk);
  glm::vec3 colourAt(const VolumeSampler& sampler, const glm::dvec3& index, float isoValue) const;

  const VoxelVolume& voxels_;
  const TissueMap* tissues_;
  IsoSurfaceMesher mesher_;
  std::map<IsoSurfaceMesher::ChunkKey, GlMesh, IsoSurfaceMesher::KeyLess> gpu_;
  std::vector<Vertex> scratch_;
  std::size_t uploads_ = 0;
};

}  // namespace millsim
