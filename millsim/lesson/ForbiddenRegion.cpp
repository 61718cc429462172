#include "millsim/lesson/ForbiddenRegion.h"

namespace millsim {

const NodeType& ForbiddenRegion::type() {
  static const NodeType t = makeNodeType<ForbiddenRegion>(
      "ForbiddenRegion", "children", "MillSim lessons",
      "A region not to cut: reports whether, and when first, the burr removed material inside.");
  return t;
}

}  // namespace millsim
