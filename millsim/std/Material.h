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
};

}  // namespace millsim
