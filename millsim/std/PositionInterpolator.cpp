#include "millsim/std/PositionInterpolator.h"

#include <algorithm>

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
  const auto& k = key.get();
  const auto& v = keyValue.get();
  const std::size_t n = std::min(k.size(), v.size());
  if (n == 0) return false;
  const KeySegment s = keySegment(k, n, set_fraction.get());
  value_changed.set(s.t == 0.f ? v[s.i] : v[s.i] + s.t * (v[s.i + 1] - v[s.i]));
  return true;
}

}  // namespace millsim
