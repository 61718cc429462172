#pragma once
// PointShell: the paper's point shell of the milled object (Algorithm #3's
// "MPO"): one point per surface voxel (two for a voxel-thin sheet, one per
// face), moved from the voxel onto the iso-surface along its outward normal.
// A surface voxel is inside (density > iso) with at least one of its six
// neighbours outside. With scale s > 1 (the paper's reduced resolution) the
// volume is first reduced over s³ blocks (each coarse voxel takes the densest
// of its fine voxels, so thin material never vanishes) and the surface voxels
// of that coarse field are used, each starting from the centroid of its
// block's material, which gives roughly 1/s² as many points.
//
// Points are bucketed by blocks of 8³ coarse voxels, and buckets by groups of
// 4³ (super-buckets), each with a tight bounding box: a box query visits only
// the super-buckets and buckets whose boxes overlap (the paper's octree). After
// milling, update() recomputes only the coarse voxels a stamp can have
// affected (the changed voxels' box, widened by the neighbour and normal
// stencils) from one dense copy of that box, and merges them into the buckets
// they fall in. An update never allocates. A build does the same for every
// bucket, on TBB's threads, and lays the points out in bucket order.
//
// Memory: all points live in one array (points_, with each point's cell in
// cells_), a bucket is a range of it [begin, begin + capacity) of which it
// uses `size`. The array is laid out tight at build and followed by headroom
// for milling (kHeadroomPerPoint slots per point built, at least
// kMinHeadroom): milling removes material but exposes new surface, so a
// bucket can grow, and a bucket inside the material, with no points at build,
// can gain them. A bucket that outgrows its range moves to the headroom's
// free end with some slack (its old range is left as a hole). When the free
// end is used up, the array is compacted in place (every bucket slid down in
// array order, holes and slack returned to the free end: O(points), no
// allocation, counted by compactions()). Only if the points then still do not
// fit does a bucket keep what fits and drop the rest, counted by
// droppedPoints() — the documented cap; the shell is then no longer what a
// rebuild gives until the owner builds a new one. Every buffer is written
// when it is made, so memoryBytes() is resident memory, not reserved
// capacity, and the haptic thread never page-faults into the headroom.
#include <cstdint>
#include <limits>
#include <vector>

#include <glm/vec3.hpp>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

#include "millsim/haptics/PointShellQuery.h"
#include "millsim/volume/DirtyBlocks.h"

namespace millsim {

// Built from and updated against the voxels (PointShell.cpp reads them through
// OpenVDB); queried by Algorithm #3 as a PointShellQuery (millsim/haptics),
// which holds the points and boxes and nothing of the voxels.
class VoxelVolume;

class PointShell : public PointShellQuery {
public:
  // Points a bucket may hold: its capacity, reserved once (one per voxel; a
  // sheet voxel has two, but its outside neighbours have none).
  static constexpr std::size_t kMaxBucketPoints = std::size_t(kBucket) * kBucket * kBucket;
  // Headroom for milling, in point slots: kHeadroomPerPoint per point at
  // build, at least kMinHeadroom (room to move a few full buckets).
  static constexpr std::size_t kHeadroomPerPoint = 2;
  static constexpr std::size_t kMinHeadroom = 8 * kMaxBucketPoints;

  // headroomPerPoint and minHeadroom: the headroom's size (tests shrink it).
  PointShell(const VoxelVolume& volume, float isoValue, int scale, std::size_t headroomPerPoint = kHeadroomPerPoint,
             std::size_t minHeadroom = kMinHeadroom);

  // Bytes of every buffer the shell holds, headroom and scratch included; all
  // of it is written at construction, so this is what the shell keeps resident.
  std::size_t memoryBytes() const;
  // Point slots: held points plus headroom (free end, holes and slack).
  std::size_t capacity() const { return points_.size(); }
  std::size_t headroom() const { return points_.size() - count_; }
  // How often a growing bucket moved to the free end, the array was
  // compacted, and points were dropped because the headroom was used up.
  std::size_t relocations() const { return relocations_; }
  std::size_t compactions() const { return compactions_; }
  std::size_t droppedPoints() const { return droppedPoints_; }

  // Rebuilds the buckets affected by changes in the given 8³ voxel blocks
  // (leaf origins, as DirtyBlocks reports them). Returns the number of buckets rebuilt.
  int update(const VoxelVolume& volume, const std::vector<BlockOrigin>& dirtyLeafOrigins);
  // The fast path: recomputes only the coarse voxels within reach of the
  // voxels `dirty` marked (its voxel box); falls back to the block path above
  // when the box is larger than the scratch space reserved. Same result.
  int update(const VoxelVolume& volume, const DirtyBlocks& dirty);
  // Rebuilds every bucket (after changes this shell missed). Does not allocate.
  void rebuildAll(const VoxelVolume& volume);

  // All points in a stable order (bucket order, then scan order): for tests.
  std::vector<ShellPoint> points() const;

private:
  // Accessor: the grid's const accessor (a template so that this header stays free of OpenVDB).
  template <class Accessor> float coarse(const Accessor& acc, int I, int J, int K) const;
  // The shell points of coarse voxel (I, J, K) with value v and six
  // neighbours n (−x, +x, −y, +y, −z, +z): none inside or outside the
  // surface, two for a voxel-thin sheet (one per face), else one. `fine(i, j,
  // k)` reads a fine voxel (within s + 1 voxels of the block). Shared by both
  // paths so that an update gives bit-for-bit what a rebuild gives.
  template <class Fine>
  int makePoints(const Fine& fine, float v, const float n[6], int I, int J, int K, ShellPoint out[2]) const;
  // The centroid of the fine voxels of coarse voxel (I, J, K) that hold
  // material, in fine index units.
  template <class Fine> glm::dvec3 materialCentre(const Fine& fine, int I, int J, int K) const;
  // From `at` (fine index units, inside) out along `outward` to the iso-surface
  // of the trilinear fine field, at most s fine voxels away along each axis.
  // `startValue`: the field at `at` when the caller knows it (a voxel centre
  // at scale 1 is the voxel's own value), else NaN.
  template <class Fine>
  glm::dvec3 ontoSurface(const Fine& fine, glm::dvec3 at, const glm::dvec3& outward, double startValue) const;
  // Recomputes bucket b's points from the voxels into merged_; returns how many.
  template <class Accessor> std::size_t computeBucket(const Accessor& acc, int b);
  // Makes merged_[0, n) bucket b's points: in its range if they fit, else in
  // a new one at the free end (tight: exactly n long, for a fresh layout).
  void store(int b, std::size_t n, bool tight);
  // Slides every bucket down in array order, ranges cut to their size.
  void compact();
  void refreshSuper(int s);
  bool updateRegion(const VoxelVolume& volume, glm::ivec3 voxelLo, glm::ivec3 voxelHi, int& rebuilt);
  // Calls emit(I, J, K, points, n) for each coarse voxel of [lo, hi] that has
  // shell points, in scan order, from dense copies of the region (Dense: the
  // fine and coarse copies PointShell.cpp makes). Build and update share it.
  template <class Dense, class Emit> void scanDense(const Dense& dense, glm::ivec3 lo, glm::ivec3 hi, Emit&& emit) const;

  const VoxelVolume* volume_;
  float iso_;
  glm::ivec3 coarseDims_;
  glm::ivec3 bucketDims_;
  glm::ivec3 superDims_;
  std::vector<std::uint16_t> cells_;  // parallel to points_
  std::size_t tail_ = 0;
  std::vector<int> order_;            // compact()'s scratch: the buckets that hold material
  std::size_t relocations_ = 0, compactions_ = 0, droppedPoints_ = 0;
  // Scratch for updateRegion: dense fine values, coarse values, a merged bucket.
  // The fine copy is scratchEdge_³ voxels: kTileEdge³ plus the stencils'
  // margins (6s + 2), at most kScratchEdge³. One stamp of a burr up to about
  // 1.5 mm (at 0.1 mm voxels) fits; larger boxes (a dormant shell catching
  // up) are covered by cubes of kTileEdge (fewer past s = 5).
  static constexpr int kScratchEdge = 64, kTileEdge = 32;
  int scratchEdge_;
  std::vector<float> fineScratch_, coarseScratch_;
  std::vector<ShellPoint> merged_;
  std::vector<std::uint16_t> mergedCells_;
};

}  // namespace millsim
