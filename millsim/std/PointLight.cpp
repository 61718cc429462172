#include "millsim/std/PointLight.h"

namespace millsim {

const NodeType& PointLight::type() {
  static const NodeType t = makeNodeType<PointLight>("PointLight", "children", "Lighting", "A light at a point, shining every way.");
  return t;
}

}  // namespace millsim
