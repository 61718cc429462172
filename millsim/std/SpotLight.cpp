#include "millsim/std/SpotLight.h"

namespace millsim {

const NodeType& SpotLight::type() {
  static const NodeType t = makeNodeType<SpotLight>("SpotLight", "children", "Lighting", "A light at a point, shining a cone.");
  return t;
}

}  // namespace millsim
