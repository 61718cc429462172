#include "millsim/std/IntegerTrigger.h"

namespace millsim {

const NodeType& IntegerTrigger::type() {
  static const NodeType t = makeNodeType<IntegerTrigger>(
      "IntegerTrigger", "children", "EventUtilities",
      "Sends integerKey on triggerValue whenever set_boolean receives TRUE (e.g. a key into Switch.whichChoice).");
  return t;
}

bool IntegerTrigger::processEvents() {
  if (!takeEvent(set_boolean, seen_) || !set_boolean.get()) return false;
  triggerValue.set(integerKey.get());
  return true;
}

}  // namespace millsim
