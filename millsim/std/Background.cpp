#include "millsim/std/Background.h"

namespace millsim {

const NodeType& Background::type() {
  static const NodeType t = makeNodeType<Background>("Background", "children", "Environmental effects", "Background colours.");
  return t;
}

}  // namespace millsim
