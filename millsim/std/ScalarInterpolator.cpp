#include "millsim/std/ScalarInterpolator.h"

#include "millsim/std/KeyFrames.h"

namespace millsim {

const NodeType& ScalarInterpolator::type() {
  static const NodeType t = makeNodeType<ScalarInterpolator>(
      "ScalarInterpolator", "children", "Interpolation",
      "Interpolates a float linearly between key values; evaluated by the event clock when set_fraction arrives.");
  return t;
}

bool ScalarInterpolator::processEvents() {
  if (!takeEvent(set_fraction, seen_)) return false;
  const auto v = interpolate(key.get(), keyValue.get(), set_fraction.get(),
                             [](const auto& a, const auto& b, float t) { return a + t * (b - a); });
  if (!v) return false;
  value_changed.set(*v);
  return true;
}

}  // namespace millsim
