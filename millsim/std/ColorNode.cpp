#include "millsim/std/ColorNode.h"

namespace millsim {

const NodeType& ColorNode::type() {
  static const NodeType t = makeNodeType<ColorNode>("Color", "color", "Rendering",
                                                    "Colours of a mesh's vertices or faces; they replace the Material's diffuseColor.");
  return t;
}

}  // namespace millsim
