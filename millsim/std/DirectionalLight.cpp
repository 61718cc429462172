#include "millsim/std/DirectionalLight.h"

namespace millsim {

const NodeType& DirectionalLight::type() {
  static const NodeType t = makeNodeType<DirectionalLight>("DirectionalLight", "children", "Lighting", "A light from one direction.");
  return t;
}

}  // namespace millsim
