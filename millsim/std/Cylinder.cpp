#include "millsim/std/Cylinder.h"

namespace millsim {

const NodeType& Cylinder::type() {
  static const NodeType t = makeNodeType<Cylinder>("Cylinder", "geometry", "Geometry3D", "A cylinder along local +Y.");
  return t;
}

}  // namespace millsim
