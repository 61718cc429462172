#include "millsim/std/Sphere.h"

namespace millsim {

const NodeType& Sphere::type() {
  static const NodeType t = makeNodeType<Sphere>("Sphere", "geometry", "Geometry3D", "A sphere centred on the origin.");
  return t;
}

}  // namespace millsim
