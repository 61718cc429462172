#pragma once
// CutCap: one volume's CutSection on the GPU — its image as a texture and a
// quad on the plane — kept in step with the plane and with milling (only the
// re-sampled texels are uploaded again). Internal to the graphics library;
// every call needs the renderer's GL context current.
#include <memory>
#include <vector>

#include "millsim/graphics/CutSection.h"
#include "millsim/graphics/GlMesh.h"

namespace millsim {

class CutCap {
public:
  CutCap(const VoxelVolume& voxels, float isoValue, const TissueMap* tissues);
  ~CutCap();
  CutCap(const CutCap&) = delete;
  CutCap& operator=(const CutCap&) = delete;

  // As CutSection::aim, uploading a new section; false: nothing to draw.
  bool aim(const glm::dvec4& plane, const glm::dmat4& localToWorld);
  void update(const std::vector<BlockOrigin>& blocks);
  void invalidate() { section_.invalidate(); }
  // Binds the texture to unit 0 and draws the quad (world coordinates).
  void draw() const;
  const CutSection& section() const { return section_; }

private:
  CutSection section_;
  unsigned texture_ = 0;
  GlMesh quad_;
};

}  // namespace millsim
