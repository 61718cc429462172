#pragma once
// ShadedProgram: the one GLSL program the renderer draws everything with —
// two-sided Blinn-Phong lit by a headlight and a fill light, per-vertex or
// per-draw colour, up to kMaxClipPlanes world-space clip planes. Internal to
// the graphics library; needs the GL context current.
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

  // Per frame: camera and lights (directions towards the light, world frame).
  void use(const Camera& camera, const glm::vec3& headlight, const glm::vec3& fillLight);
  // Per draw. `colour` null: the vertices' own colours (volumes). `tintInside`:
  // colour back faces (the inside of a cut surface) a darker red-brown.
  void setObject(const glm::dmat4& model, const DrawMaterial& material, const glm::vec3* colour, bool tintInside,
                 const ClipPlanes& clipPlanes);

private:
  unsigned program_ = 0;
  int uModel_, uViewProj_, uNormalMatrix_, uEye_, uHead_, uFill_, uSpecular_, uShininess_, uEmissive_, uAmbient_,
      uTint_, uClipCount_, uClip_, uOpacity_;
};

}  // namespace millsim
