#include "millsim/std/Appearance.h"

namespace millsim {

const NodeType& Appearance::type() {
  static const NodeType t = makeNodeType<Appearance>("Appearance", "appearance", "Shape", "Visual properties of a Shape.");
  return t;
}

}  // namespace millsim
