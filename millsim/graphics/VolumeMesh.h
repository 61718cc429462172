#pragma once
// VolumeMesh: the iso-surface of one voxel volume on the GPU. Meshes with
// IsoSurfaceMesher (16³-cell chunks) and keeps one GlMesh per chunk, so that
// after milling only the chunks the changed blocks touch are re-extracted and
// re-uploaded. Vertex colours come from the tissue just inside the surface
// (its Tissue colour), or without tissues from the density there, so enamel,
// dentin and whatever a cut exposes look different.
//
// Levels of detail: level l meshes the volume averaged over 2^l × 2^l × 2^l
// voxels (CoarseVolume.h; level 0 is every voxel, each level a quarter of the
// triangles of the one below), kept in step with milling the same way. The
// drawer picks the finest level whose voxel covers at least about 1.5 pixels:
// marching cubes makes about two triangles per surface voxel, so finer
// triangles would be smaller than a pixel, costing vertex work llvmpipe pays
// for and showing nothing. A level is meshed when it is first drawn and only
// then kept in step: a tooth at 25 µm voxels seen whole is drawn at level 3
// (its 0.2 mm voxels, what level 1 shows of a 0.1 mm tooth), and its every-
// voxel mesh, eight seconds to make and most of each milling frame's
// re-meshing, is made only if the view comes close enough to show it.
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

  static constexpr int kLevels = 4;  // every voxel, then averaged over 2³, 4³ and 8³

  void build();                                             // the levels made so far, afresh
  void update(const std::vector<BlockOrigin>& blocks);   // after these 8³ blocks changed
  // Makes `level` (clamped to the levels the volume has) if it has not been made.
  void prepare(int level);
  // A level prepare() made (clamped the same way), in the volume's local frame; nothing if it was not.
  void draw(int level = 0) const;
  double voxelSize() const;  // the smallest edge (m)

  int levels() const { return levelCount_; }  // how many this volume has (fewer for coarse CT voxels)
  std::size_t triangles(int level = 0) const;  // 0 for a level not made
  std::size_t chunks() const;                  // of the levels made
  std::size_t uploads() const { return uploads_; }  // chunk uploads since construction (every level)

private:
  struct Level {
    int factor = 1;
    std::unique_ptr<VoxelVolume> own;  // the averaged copy (level 0 meshes the caller's voxels)
    std::unique_ptr<IsoSurfaceMesher> mesher;
    std::map<IsoSurfaceMesher::ChunkKey, GlMesh, IsoSurfaceMesher::KeyLess> gpu;
    // Where its coarse voxels' centres are in level 0's local frame, relative
    // to its own centred frame (half a fine voxel per odd remainder).
    glm::dvec3 offset{0.0};
    bool made = false;
  };
  void make(Level& level);
  void upload(Level& level, const IsoSurfaceMesher::ChunkKey& key, const MeshChunk& chunk, const glm::dvec3& shift);
  glm::vec3 colourAt(const VolumeSampler& sampler, const glm::dvec3& index, float isoValue) const;

  const VoxelVolume& voxels_;
  const TissueMap* tissues_;
  float iso_;
  Level levels_[kLevels];
  int levelCount_ = 0;  // the levels this volume has (coarse voxels within kMaxVoxelSize)
  std::vector<Vertex> scratch_;
  std::size_t uploads_ = 0;
};

}  // namespace millsim
