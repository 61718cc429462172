#pragma once
// IsoSurfaceMesher: the triangle mesh of a VoxelVolume's iso-surface, for
// graphics. The volume is cut into chunks of chunkSize³ cells, each with its
// own mesh, so that after a milling stamp only the few chunks the stamp
// touched are re-extracted and re-uploaded.
//
// What the mesh is: the surface density == isoValue of the sampled field
// (samples at voxel centres, density > isoValue inside), extracted per chunk
// with VTK's flying edges. The volume's outer faces are NOT closed: where
// material reaches the border of the data the mesh is open, and a volume that
// is material everywhere has no surface at all.
//
// Chunk (cx, cy, cz) covers the cells between samples c·s and c·s + s on each
// axis (s = chunkSize), so neighbouring chunks read the same boundary samples:
// the union of the chunks is the whole-volume extraction triangle for
// triangle, and vertices on chunk borders are bit-identical on both sides
// (watertight). Normals are not VTK's per-chunk normals, which use one-sided
// differences at the chunk's faces and would shade a visible 16-voxel grid;
// they are Sobel gradients (each central difference averaged 1-2-1 over the
// two other axes) of the samples smoothed 1-2-1 along every axis, read across
// chunk borders, so a voxel change dirties the chunks within two samples of
// it, not only those whose cells contain it.
//
// Threads: not thread-safe. buildAll() and update() read the volume's grid on
// the calling thread, and nothing may write those voxels meanwhile — which is
// why graphics meshes its own copy of the voxels, not the haptic thread's.
#include <cstdint>
#include <map>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

#include "millsim/volume/DirtyBlocks.h"
#include "millsim/volume/VoxelVolume.h"

namespace millsim {

struct MeshChunk {
  std::vector<glm::vec3> positions;    // volume-local coordinates, metres
  std::vector<glm::vec3> normals;      // unit, out of the object (towards lower density)
  std::vector<std::uint32_t> indices;  // triangles, counter-clockwise seen from outside
  // Strictly increases every time this chunk is re-extracted (taken from one
  // counter per mesher, so a chunk that vanishes and comes back never reuses
  // a version graphics has already uploaded).
  std::uint64_t version = 0;
};

class IsoSurfaceMesher {
public:
  // Chunk coordinate: chunk k starts at voxel k·chunkSize on each axis.
  using ChunkKey = glm::ivec3;
  // z, then y, then x: iteration follows the volume's memory order.
  struct KeyLess {
    bool operator()(const ChunkKey& a, const ChunkKey& b) const {
      return a.z != b.z ? a.z < b.z : a.y != b.y ? a.y < b.y : a.x < b.x;
    }
  };
  using ChunkMap = std::map<ChunkKey, MeshChunk, KeyLess>;

  // Keeps a reference to the volume, which must outlive the mesher. Builds
  // nothing yet. Throws std::invalid_argument unless 1 <= chunkSize <= 256.
  IsoSurfaceMesher(const VoxelVolume& volume, float isoValue, int chunkSize = 16);
  ~IsoSurfaceMesher();
  IsoSurfaceMesher(IsoSurfaceMesher&&) noexcept;
  IsoSurfaceMesher& operator=(IsoSurfaceMesher&&) noexcept;

  // Extracts every chunk afresh. Chunks that hold no leaf of the grid are
  // skipped without reading a voxel (outside leaves the grid holds air).
  void buildAll();

  // Re-extracts the chunks that may have changed because voxels inside the
  // given 8³ leaves changed (origins as openvdb reports them: multiples of 8).
  // Returns the keys of chunks whose mesh was replaced or removed; look each
  // up with chunk(): nullptr means it is now empty and its buffers can go.
  std::vector<ChunkKey> update(const std::vector<BlockOrigin>& dirtyLeafOrigins);

  // Only chunks that contain triangles.
  const ChunkMap& chunks() const { return chunks_; }
  const MeshChunk* chunk(const ChunkKey& key) const;
  std::size_t chunkCount() const { return chunks_.size(); }
  std::size_t triangleCount() const;
  double totalArea() const;  // m²

  // Number of chunks along each axis: ceil((dims − 1) / chunkSize).
  glm::ivec3 chunkGrid() const { return chunkGrid_; }
  int chunkSize() const { return chunkSize_; }
  float isoValue() const { return isoValue_; }

private:
  struct Extractor;  // the VTK pipeline and scratch buffers, reused for every chunk

  void extract(const ChunkKey& key, std::vector<ChunkKey>* changed);

  const VoxelVolume* volume_;
  float isoValue_;
  int chunkSize_;
  glm::ivec3 chunkGrid_;
  std::uint64_t nextVersion_ = 1;
  ChunkMap chunks_;
  std::unique_ptr<Extractor> extractor_;
};

}  // namespace millsim
