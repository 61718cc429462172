#include "millsim/std/OrientationInterpolator.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/quaternion.hpp>


namespace millsim {

const NodeType& OrientationInterpolator::type() {
  static const NodeType t = makeNodeType<OrientationInterpolator>(
      "OrientationInterpolator", "children", "Interpolation",
      "Interpolates an orientation between key values by slerp along the shorter arc; evaluated by the event "
      "clock when set_fraction arrives.");
  return t;
}

namespace {

Rotation slerp(const Rotation& a, const Rotation& b, float t) {
  glm::dquat qa = glm::normalize(glm::dquat(a.quat())), qb = glm::normalize(glm::dquat(b.quat()));
  if (glm::dot(qa, qb) < 0.0) qb = -qb;  // q and -q are one rotation: take the shorter arc
  const double d = std::clamp(glm::dot(qa, qb), -1.0, 1.0);
  const double theta = std::acos(d);
  glm::dquat q;
  if (theta < 1e-9) {
    q = qa;
  } else {
    const double s = std::sin(theta);
    q = qa * (std::sin((1.0 - t) * theta) / s) + qb * (std::sin(t * theta) / s);
  }
  q = glm::normalize(q);
  if (q.w < 0.0) q = -q;  // angle in [0, π]
  const double angle = 2.0 * std::acos(std::clamp(q.w, -1.0, 1.0));
  const double sinHalf = std::sqrt(std::max(0.0, 1.0 - q.w * q.w));
  if (sinHalf < 1e-12) return Rotation{a.axis, 0.f};
  return Rotation{glm::vec3(glm::dvec3(q.x, q.y, q.z) / sinHalf), float(angle)};
}

}  // namespace

bool OrientationInterpolator::processEvents() { return sendInterpolated(keyValue, value_changed, slerp); }

}  // namespace millsim
