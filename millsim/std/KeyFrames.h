#pragma once
// Where a fraction falls among an interpolator's keys (X3D 19.2.2): the key
// index i and the weight t of key i + 1 in [0, 1]. Below the first key the
// first value holds, above the last the last.
#include <algorithm>
#include <cstddef>
#include <optional>
#include <vector>

namespace millsim {

struct KeySegment {
  std::size_t i = 0;
  float t = 0.f;
};

// `count`: how many keys have a value (the shorter of key and keyValue); at least 1.
inline KeySegment keySegment(const std::vector<float>& key, std::size_t count, float fraction) {
  if (count <= 1 || fraction <= key[0]) return {0, 0.f};
  if (fraction >= key[count - 1]) return {count - 1, 0.f};
  std::size_t i = 0;
  while (i + 2 < count && fraction >= key[i + 1]) ++i;
  const float span = key[i + 1] - key[i];
  return {i, span > 0.f ? (fraction - key[i]) / span : 1.f};  // equal keys: a step
}

// An interpolator's value at `fraction`: the key value where it falls on a key,
// else mix(value i, value i + 1, t). None when no key has a value (X3D leaves
// that undefined; the interpolator sends nothing).
template <class V, class Mix>
std::optional<V> interpolate(const std::vector<float>& key, const std::vector<V>& value, float fraction, Mix&& mix) {
  const std::size_t n = std::min(key.size(), value.size());
  if (n == 0) return std::nullopt;
  const KeySegment s = keySegment(key, n, fraction);
  return s.t == 0.f ? value[s.i] : mix(value[s.i], value[s.i + 1], s.t);
}

}  // namespace millsim
