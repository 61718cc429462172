#include "millsim/std/PositionInterpolator.h"

namespace millsim {

const NodeType& PositionInterpolator::type() {
  static const NodeType t = makeNodeType<PositionInterpolator>(
      "PositionInterpolator", "children", "Interpolation",
      "Interpolates a position linearly between key values; evaluated by the event clock when set_fraction arrives.");
  return t;
}

bool PositionInterpolator::processEvents() {
  return sendInterpolated(keyValue, value_changed, [](const auto& a, const auto& b, float t) { return a + t * (b - a); });
}

}  // namespace millsim
