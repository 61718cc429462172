#include "millsim/std/Group.h"

namespace millsim {

const NodeType& Group::type() {
  static const NodeType t = makeNodeType<Group>("Group", "children", "Grouping", "Groups child nodes.");
  return t;
}

}  // namespace millsim
