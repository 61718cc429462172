#include "millsim/std/BooleanFilter.h"

namespace millsim {

const NodeType& BooleanFilter::type() {
  static const NodeType t = makeNodeType<BooleanFilter>(
      "BooleanFilter", "children", "EventUtilities",
      "Sends a boolean event on inputTrue or inputFalse by its value, and its negation on inputNegate.");
  return t;
}

bool BooleanFilter::processEvents() {
  if (!takeEvent(set_boolean, seen_)) return false;
  const bool v = set_boolean.get();
  (v ? inputTrue : inputFalse).set(v);
  inputNegate.set(!v);
  return true;
}

}  // namespace millsim
