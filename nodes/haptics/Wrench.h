#pragma once
// Limits on what may be sent to a device: magnitudes are scaled down to the
// limits (direction kept), and anything non-finite becomes zero.
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace millsim {

inline glm::dvec3 clampMagnitude(const glm::dvec3& v, double limit) {
  if (!(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z))) return glm::dvec3(0.0);
  const double m = glm::length(v);
  return m > limit && m > 0.0 ? v * (limit / m) : v;
}

}  // namespace millsim
