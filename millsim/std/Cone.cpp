#include "millsim/std/Cone.h"

namespace millsim {

const NodeType& Cone::type() {
  static const NodeType t = makeNodeType<Cone>("Cone", "geometry", "Geometry3D", "A cone along +Y, centred on the origin.");
  return t;
}

}  // namespace millsim
