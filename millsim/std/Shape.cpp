#include "millsim/std/Shape.h"

namespace millsim {

const NodeType& Shape::type() {
  static const NodeType t = makeNodeType<Shape>("Shape", "children", "Shape", "Geometry with an appearance.");
  return t;
}

}  // namespace millsim
