#pragma once
#include "millsim/core/NodeKinds.h"

namespace millsim {

// Phong material parameters, as X3D defines them.
class Material : public MaterialNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  SFColor diffuseColor{this, "diffuseColor", Access::InputOutput, Color{glm::vec3(0.8f)}, "Diffuse colour.", Range::closed(0, 1)};
  SFColor specularColor{this, "specularColor", Access::InputOutput, Color{glm::vec3(0.f)}, "Specular colour.", Range::closed(0, 1)};
  SFColor emissiveColor{this, "emissiveColor", Access::InputOutput, Color{glm::vec3(0.f)}, "Emitted colour.", Range::closed(0, 1)};
  SFFloat ambientIntensity{this, "ambientIntensity", Access::InputOutput, 0.2f,
                           "Fraction of diffuse colour reflected from ambient light.", Range::closed(0.0, 1.0)};
  SFFloat shininess{this, "shininess", Access::InputOutput, 0.2f, "Sharpness of highlights.", Range::closed(0.0, 1.0)};
  SFFloat transparency{this, "transparency", Access::InputOutput, 0.f, "0 = opaque.", Range::closed(0.0, 1.0)};
  SFFloat normalScale{this, "normalScale", Access::InputOutput, 1.f, "Scale of normalTexture's normals. Accepted; not acted on by MillSim.",
                      Range::closed(0, 1e4)};
  SFFloat occlusionStrength{this, "occlusionStrength", Access::InputOutput, 1.f, "Weight of occlusionTexture. Accepted; not acted on by MillSim.",
                            Range::closed(0.0, 1.0)};
  SFString ambientTextureMapping{this, "ambientTextureMapping", Access::InputOutput, "", "Texture coordinates of ambientTexture. Accepted; not acted on by MillSim."};
  SFString diffuseTextureMapping{this, "diffuseTextureMapping", Access::InputOutput, "", "Texture coordinates of diffuseTexture. Accepted; not acted on by MillSim."};
  SFString emissiveTextureMapping{this, "emissiveTextureMapping", Access::InputOutput, "", "Texture coordinates of emissiveTexture. Accepted; not acted on by MillSim."};
  SFString normalTextureMapping{this, "normalTextureMapping", Access::InputOutput, "", "Texture coordinates of normalTexture. Accepted; not acted on by MillSim."};
  SFString occlusionTextureMapping{this, "occlusionTextureMapping", Access::InputOutput, "", "Texture coordinates of occlusionTexture. Accepted; not acted on by MillSim."};
  SFString shininessTextureMapping{this, "shininessTextureMapping", Access::InputOutput, "", "Texture coordinates of shininessTexture. Accepted; not acted on by MillSim."};
  SFString specularTextureMapping{this, "specularTextureMapping", Access::InputOutput, "", "Texture coordinates of specularTexture. Accepted; not acted on by MillSim."};
};

}  // namespace millsim
