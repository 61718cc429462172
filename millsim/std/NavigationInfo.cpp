#include "millsim/std/NavigationInfo.h"

namespace millsim {

const NodeType& NavigationInfo::type() {
  static const NodeType t = makeNodeType<NavigationInfo>("NavigationInfo", "children", "Navigation", "Viewer navigation and headlight.");
  return t;
}

}  // namespace millsim
