#include "millsim/std/ScalarInterpolator.h"

namespace millsim {

const NodeType& ScalarInterpolator::type() {
  static const NodeType t = makeNodeType<ScalarInterpolator>(
      "ScalarInterpolator", "children", "Interpolation",
      "Interpolates a float linearly between key values; evaluated by the event clock when set_fraction arrives.");
  return t;
}

bool ScalarInterpolator::processEvents() {
  return sendInterpolated(keyValue, value_changed, [](const auto& a, const auto& b, float t) { return a + t * (b - a); });
}

}  // namespace millsim
