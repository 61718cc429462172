#include "millsim/lesson/MillingTarget.h"

namespace millsim {

const NodeType& MillingTarget::type() {
  static const NodeType t = makeNodeType<MillingTarget>(
      "MillingTarget", "children", "MillSim lessons",
      "A region to remove: reports how much of its material the burr removed.");
  return t;
}

}  // namespace millsim
