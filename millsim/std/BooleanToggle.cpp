#include "millsim/std/BooleanToggle.h"

namespace millsim {

const NodeType& BooleanToggle::type() {
  static const NodeType t = makeNodeType<BooleanToggle>(
      "BooleanToggle", "children", "EventUtilities",
      "Negates toggle at each TRUE set_boolean (a key press that switches something on, then off).");
  return t;
}

bool BooleanToggle::processEvents() {
  if (!takeEvent(set_boolean, seen_) || !set_boolean.get()) return false;
  toggle.set(!toggle.get());
  return true;
}

}  // namespace millsim
