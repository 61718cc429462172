#include "millsim/std/ScalarInterpolator.h"

#include <algorithm>

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
  const auto& k = key.get();
  const auto& v = keyValue.get();
  const std::size_t n = std::min(k.size(), v.size());
  if (n == 0) return false;  // nothing to interpolate: no event (X3D leaves it undefined)
  const KeySegment s = keySegment(k, n, set_fraction.get());
  value_changed.set(s.t == 0.f ? v[s.i] : v[s.i] + s.t * (v[s.i + 1] - v[s.i]));
  return true;
}

}  // namespace millsim
