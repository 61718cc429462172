#pragma once
// VolumeMesh: the iso-surface of one voxel volume on the GPU. Meshes with
// IsoSurfaceMesher (16³-cell chunks) and keeps one GlMesh per chunk, so that
// after milling only the chunks the changed blocks touch are re-extracted and
// re-uploaded. Vertex colours come from the tissue just inside the surface
// (its Tissue colour), or without tissues from the density there, so enamel,
// dentin and whatever a cut exposes look different.
//
// Two levels of detail: level 0 meshes every voxel; level 1 meshes the
// volume averaged over 2×2×2 voxels (a quarter of the triangles), kept in
// step with milling the same way. The drawer picks level 1 where a voxel
// covers less than about 1.5 pixels: marching cubes makes about two
// triangles per surface voxel, so level 0's triangles would then be smaller
// than a pixel, costing vertex work llvmpipe pays for and showing nothing.
// Internal to the graphics library; every call needs the renderer's GL
// context current.
#include <map>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

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
  // Level 0 (every voxel) or 1 (2×2×2 averaged); both in the volume's local frame.
  void draw(int level = 0) const;
  double voxelSize() const;  // the smallest edge (m)

  std::size_t triangles(int level = 0) const { return levels_[level].mesher->triangleCount(); }
  std::size_t chunks() const { return levels_[0].gpu.size(); }
  std::size_t uploads() const { return uploads_; }  // chunk uploads since construction (both levels)

private:
  struct Level {
    std::unique_ptr<VoxelVolume> own;  // level 1's averaged copy (level 0 meshes the caller's voxels)
    std::unique_ptr<IsoSurfaceMesher> mesher;
    std::map<IsoSurfaceMesher::ChunkKey, GlMesh, IsoSurfaceMesher::KeyLess> gpu;
  };
  void upload(Level& level, const IsoSurfaceMesher::ChunkKey& key, const MeshChunk& chunk, const glm::dvec3& shift);
  glm::vec3 colourAt(const VolumeSampler& sampler, const glm::dvec3& index, float isoValue) const;

  const VoxelVolume& voxels_;
  const TissueMap* tissues_;
  float iso_;
  Level levels_[2];
  // Level 1's local frame is centred on its own grid: where a dimension is
  // odd it sits half a voxel off level 0's, and its vertices are moved by this.
  glm::dvec3 coarseOffset_{0.0};
  std::vector<Vertex> scratch_;
  std::size_t uploads_ = 0;
};

}  // namespace millsim
