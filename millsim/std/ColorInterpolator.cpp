#include "millsim/std/ColorInterpolator.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>


namespace millsim {

const NodeType& ColorInterpolator::type() {
  static const NodeType t = makeNodeType<ColorInterpolator>(
      "ColorInterpolator", "children", "Interpolation",
      "Interpolates a colour between key values in HSV space (the hue the shorter way round); evaluated by the "
      "event clock when set_fraction arrives.");
  return t;
}

namespace {

// Hue in [0, 6) (sextants), saturation and value in [0, 1]. A grey has hue 0.
glm::vec3 toHsv(const glm::vec3& c) {
  const float mx = std::max({c.r, c.g, c.b}), mn = std::min({c.r, c.g, c.b});
  const float d = mx - mn;
  float h = 0.f;
  if (d > 0.f) {
    if (mx == c.r) h = std::fmod((c.g - c.b) / d + 6.f, 6.f);
    else if (mx == c.g) h = (c.b - c.r) / d + 2.f;
    else h = (c.r - c.g) / d + 4.f;
  }
  return {h, mx > 0.f ? d / mx : 0.f, mx};
}

glm::vec3 toRgb(const glm::vec3& hsv) {
  const float h = hsv.x, s = hsv.y, v = hsv.z;
  auto channel = [&](float n) {
    const float k = std::fmod(n + h, 6.f);
    return v - v * s * std::clamp(std::min(k, 4.f - k), 0.f, 1.f);
  };
  return glm::clamp(glm::vec3(channel(5.f), channel(3.f), channel(1.f)), 0.f, 1.f);
}

}  // namespace

Color ColorInterpolator::mixHsv(const Color& a, const Color& b, float t) {
  glm::vec3 p = toHsv(a.rgb), q = toHsv(b.rgb);
  // A grey has no hue: take the other colour's, so that only saturation and value change.
  if (p.y == 0.f) p.x = q.x;
  if (q.y == 0.f) q.x = p.x;
  float dh = q.x - p.x;
  if (dh > 3.f) dh -= 6.f;
  else if (dh < -3.f) dh += 6.f;
  float h = p.x + t * dh;
  if (h < 0.f) h += 6.f;
  if (h >= 6.f) h -= 6.f;
  return Color{toRgb({h, p.y + t * (q.y - p.y), p.z + t * (q.z - p.z)})};
}

bool ColorInterpolator::processEvents() { return sendInterpolated(keyValue, value_changed, &ColorInterpolator::mixHsv); }

}  // namespace millsim
