#include "millsim/std/Transform.h"

#include <glm/gtc/matrix_transform.hpp>

namespace millsim {

const NodeType& Transform::type() {
  static const NodeType t =
      makeNodeType<Transform>("Transform", "children", "Grouping", "Groups child nodes in a moved, rotated, scaled frame.");
  return t;
}

glm::mat4 Transform::localMatrix() const {
  const glm::mat4 I(1.f);
  const glm::mat4 T = glm::translate(I, translation.get());
  const glm::mat4 C = glm::translate(I, center.get());
  const glm::mat4 R = glm::mat4_cast(rotation.get().quat());
  const glm::mat4 SR = glm::mat4_cast(scaleOrientation.get().quat());
  const glm::mat4 S = glm::scale(I, scale.get());
  return T * C * R * SR * S * glm::inverse(SR) * glm::inverse(C);
}

}  // namespace millsim
