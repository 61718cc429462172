#pragma once
// ShadedProgram: the one GLSL program the renderer draws everything with —
// two-sided Blinn-Phong lit by a headlight and a fill light and the scene's
// lights, per-vertex or per-draw colour, an optional texture (an image, or a
// glyph atlas for Text), up to kMaxClipPlanes world-space clip planes. Internal to
// the graphics library; needs the GL context current.
#include <cstdint>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "millsim/graphics/SceneView.h"

namespace millsim {

class ShadedProgram {
public:
  ShadedProgram();  // compiles and links; throws GraphicsError with the GLSL log
  ~ShadedProgram();
  ShadedProgram(const ShadedProgram&) = delete;
  ShadedProgram& operator=(const ShadedProgram&) = delete;

  // Per frame: camera and lights (head and fill: directions towards the
  // light, world frame; `headlightOn` false turns both off).
  void use(const Camera& camera, const glm::vec3& headlight, const glm::vec3& fillLight, bool headlightOn,
           const std::vector<DrawLight>& lights);
  // Per draw. `colour` null: the vertices' own colours (volumes). `tintInside`:
  // colour back faces (the inside of a cut surface) a darker red-brown.
  void setObject(const glm::dmat4& model, const DrawMaterial& material, const glm::vec3* colour, bool tintInside,
                 const ClipPlanes& clipPlanes);
  // After setObject (which lights it with every global light): the lights
  // that light this draw, bit i for light i (X3D's DirectionalLight scoping).
  void setLights(std::uint32_t mask);
  // After setObject, for a draw with the texture bound to unit 0.
  enum class TextureMode { None = 0, Replace = 1, Modulate = 2, Coverage = 3, Section = 4 };
  void setTexture(TextureMode mode);

private:
  unsigned program_ = 0;
  int uModel_, uViewProj_, uNormalMatrix_, uEye_, uHead_, uFill_, uSpecular_, uShininess_, uEmissive_, uAmbient_,
      uTint_, uClipCount_, uClip_, uOpacity_, uHeadOn_, uAmbientLight_, uLightCount_, uLightPos_, uLightColour_,
      uLightAtt_, uLightSpot_, uLightCone_, uTexture_, uImage_, uLightMask_;
  std::uint32_t globalLights_ = ~0u;
};

}  // namespace millsim
