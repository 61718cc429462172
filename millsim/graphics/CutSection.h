#pragma once
// CutSection: what a cut plane shows of one voxel volume — the plane's section
// through it as an image lying on the plane, each texel coloured by the tissue
// there (its Tissue colour, or by density without tissues) and carrying how
// much material is there in its alpha. The drawer lays it over the cut as a
// cap (SceneDrawer, CutCap), so a teacher reads enamel and dentin thickness
// and the wall left over the pulp from the section, as in the paper's §7.
//
// Material is what the iso-surface encloses (Milling's material fraction,
// ½ at the isoValue) and, drawn too, a soft tissue below the surface (the
// pulp), by how much of its original density milling has left. The image's
// alpha is that fraction at each texel's centre: filtered linearly and cut at
// ½ it follows the iso-contour between texels as the mesh does. Empty texels
// take a neighbour's colour so that the filtering draws no dark rim.
//
// No GL: sampled on the CPU (a texel a voxel wide, at most kMaxTexels a side)
// from the volume the drawing meshes, re-sampled only where milled blocks
// meet the plane. Not thread-safe; the volume must not change during a call.
#include <cstdint>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "millsim/volume/DirtyBlocks.h"

namespace millsim {

class TissueMap;
class VoxelVolume;

// A rectangle of texels [x0, x1) × [y0, y1).
struct TexelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x1 <= x0 || y1 <= y0; }
};

class CutSection {
public:
  static constexpr int kMaxTexels = 2048;

  // Keeps references to `voxels` and `tissues` (optional), which must outlive it.
  CutSection(const VoxelVolume& voxels, float isoValue, const TissueMap* tissues);

  // The section of the volume placed at `localToWorld` by `plane` (world:
  // unit normal n and d, n·x + d = 0). Samples it afresh if either differs
  // from the last call; false if the plane misses the volume.
  bool aim(const glm::dvec4& plane, const glm::dmat4& localToWorld);
  // After milling changed these 8³ blocks: re-samples the texels they can
  // reach. Returns the re-sampled rectangle (empty if no block meets the plane).
  TexelRect update(const std::vector<BlockOrigin>& blocks);
  // Forget the image: the next aim() samples afresh (the volume was rebuilt).
  void invalidate() { aimed_ = false; }

  bool hasSection() const { return width_ > 0; }
  int width() const { return width_; }
  int height() const { return height_; }
  // RGBA8, rows of width() texels, row 0 at corner(0)–corner(1).
  const std::vector<std::uint8_t>& rgba() const { return rgba_; }
  // The image's corners in the world (texel edges): 0 at texture (0, 0),
  // 1 at (1, 0), 2 at (1, 1), 3 at (0, 1).
  glm::dvec3 corner(int i) const;
  glm::dvec3 normal() const { return glm::dvec3(plane_); }
  double texelSize() const { return texel_; }  // m
  std::uint64_t texelsSampled() const { return sampled_; }  // since construction

private:
  void sample(const TexelRect& r);
  void fillEmptyColours(const TexelRect& r);

  const VoxelVolume& voxels_;
  const TissueMap* tissues_;
  float iso_;
  bool aimed_ = false;
  glm::dvec4 plane_{0.0};
  glm::dmat4 localToWorld_{1.0};
  glm::dmat4 worldToIndex_{1.0};
  glm::dvec4 indexPlane_{0.0};  // the plane in index coordinates
  // The image: texel (a, b)'s centre is origin_ + (a + ½)·texel_·u_ + (b + ½)·texel_·v_ (world).
  glm::dvec3 origin_{0.0}, u_{0.0}, v_{0.0};
  double texel_ = 0.0;
  int width_ = 0, height_ = 0;
  std::vector<std::uint8_t> rgba_;
  std::uint64_t sampled_ = 0;
};

}  // namespace millsim
