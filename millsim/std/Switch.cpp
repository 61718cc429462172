#include "millsim/std/Switch.h"

namespace millsim {

const NodeType& Switch::type() {
  static const NodeType t = makeNodeType<Switch>(
      "Switch", "children", "Grouping",
      "Draws the child that whichChoice names, or none. The others are neither drawn nor clip; a VolumeObject "
      "under a Switch is still placed and felt (haptic volumes are fixed for a run).");
  return t;
}

const ChildNode* Switch::chosen() const {
  const int i = whichChoice.get();
  const auto& c = children.get();
  return i >= 0 && std::size_t(i) < c.size() ? c[std::size_t(i)].get() : nullptr;
}

}  // namespace millsim
