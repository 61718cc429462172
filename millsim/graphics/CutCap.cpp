#include "millsim/graphics/CutCap.h"

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>

namespace millsim {

CutCap::CutCap(const VoxelVolume& voxels, float isoValue, const TissueMap* tissues)
    : section_(voxels, isoValue, tissues), quad_(true) {}

CutCap::~CutCap() {
  if (texture_) glDeleteTextures(1, &texture_);
}

bool CutCap::aim(const glm::dvec4& plane, const glm::dmat4& localToWorld) {
  const std::uint64_t before = section_.texelsSampled();
  if (!section_.aim(plane, localToWorld)) return false;
  if (section_.texelsSampled() == before && texture_) return true;  // the same section as last time
  if (!texture_) glGenTextures(1, &texture_);
  glBindTexture(GL_TEXTURE_2D, texture_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, section_.width(), section_.height(), 0, GL_RGBA, GL_UNSIGNED_BYTE,
               section_.rgba().data());
  // Linear, no mipmaps: the shader cuts the filtered material fraction at ½,
  // which follows the iso-contour between texels.
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  const glm::vec3 n(section_.normal());
  std::vector<Vertex> v;
  for (int i = 0; i < 4; ++i) v.push_back({glm::vec3(section_.corner(i)), n, glm::vec3(1.f)});
  quad_.upload(v, {0, 1, 2, 0, 2, 3});
  quad_.uploadTexCoords({{0.f, 0.f}, {1.f, 0.f}, {1.f, 1.f}, {0.f, 1.f}});
  return true;
}

void CutCap::update(const std::vector<BlockOrigin>& blocks) {
  const TexelRect r = section_.update(blocks);
  if (r.empty() || !texture_) return;
  glBindTexture(GL_TEXTURE_2D, texture_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, section_.width());
  glTexSubImage2D(GL_TEXTURE_2D, 0, r.x0, r.y0, r.x1 - r.x0, r.y1 - r.y0, GL_RGBA, GL_UNSIGNED_BYTE,
                  section_.rgba().data() + (std::size_t(r.y0) * std::size_t(section_.width()) + std::size_t(r.x0)) * 4);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
}

void CutCap::draw() const {
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, texture_);
  quad_.draw();
}

}  // namespace millsim
