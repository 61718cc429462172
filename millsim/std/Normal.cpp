#include "millsim/std/Normal.h"

namespace millsim {

const NodeType& Normal::type() {
  static const NodeType t = makeNodeType<Normal>("Normal", "normal", "Rendering", "Normal vectors of a mesh.");
  return t;
}

}  // namespace millsim
