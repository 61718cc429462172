#include "millsim/std/Viewpoint.h"

namespace millsim {

const NodeType& Viewpoint::type() {
  static const NodeType t = makeNodeType<Viewpoint>("Viewpoint", "children", "Navigation", "A camera position and orientation.");
  return t;
}

}  // namespace millsim
