#include "millsim/std/Box.h"

namespace millsim {

const NodeType& Box::type() {
  static const NodeType t = makeNodeType<Box>("Box", "geometry", "Geometry3D", "An axis-aligned box centred on the origin.");
  return t;
}

}  // namespace millsim
