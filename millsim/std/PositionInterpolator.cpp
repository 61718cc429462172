#include "millsim/std/PositionInterpolator.h"

#include "millsim/std/KeyFrames.h"

namespace millsim {

const NodeType& PositionInterpolator::type() {
  static const NodeType t = makeNodeType<PositionInterpolator>(
      "PositionInterpolator", "children", "Interpolation",
      "Interpolates a position linearly between key values; evaluated by the event clock when set_fraction arrives.");
  return t;
}

bool PositionInterpolator::processEvents() {
  if (!takeEvent(set_fraction, seen_)) return false;
  const auto v = interpolate(key.get(), keyValue.get(), set_fraction.get(),
                             [](const auto& a, const auto& b, float t) { return a + t * (b - a); });
  if (!v) return false;
  value_changed.set(*v);
  return true;
}

}  // namespace millsim
