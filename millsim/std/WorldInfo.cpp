#include "millsim/std/WorldInfo.h"

namespace millsim {

const NodeType& WorldInfo::type() {
  static const NodeType t = makeNodeType<WorldInfo>("WorldInfo", "children", "Core", "Scene title and notes.");
  return t;
}

}  // namespace millsim
