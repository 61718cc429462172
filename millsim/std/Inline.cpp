#include "millsim/std/Inline.h"

namespace millsim {

const NodeType& Inline::type() {
  static const NodeType t = makeNodeType<Inline>("Inline", "children", "Networking", "Includes the nodes of another X3D file.");
  return t;
}

}  // namespace millsim
