#include "millsim/std/Collision.h"

namespace millsim {

const NodeType& Collision::type() {
  static const NodeType t = makeNodeType<Collision>(
      "Collision", "children", "Navigation",
      "Groups child nodes as a Group does; its proxy (for navigation collision, which MillSim does not do) is not "
      "drawn.");
  return t;
}

}  // namespace millsim
