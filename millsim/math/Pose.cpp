#include "millsim/math/Pose.h"

#include <cmath>

#include <glm/geometric.hpp>

namespace millsim {

glm::dquat rotationBetween(const glm::dvec3& a, const glm::dvec3& b) {
  const double c = glm::dot(a, b);
  if (c > 1.0 - 1e-12) return glm::dquat(1.0, 0.0, 0.0, 0.0);
  if (c < -1.0 + 1e-12) {
    // Any axis perpendicular to a will do; pick the one least aligned with a.
    glm::dvec3 axis = std::abs(a.x) < 0.9 ? glm::cross(a, glm::dvec3(1, 0, 0)) : glm::cross(a, glm::dvec3(0, 1, 0));
    return glm::angleAxis(M_PI, glm::normalize(axis));
  }
  const glm::dvec3 axis = glm::cross(a, b);
  const double s = std::sqrt((1.0 + c) * 2.0);
  return glm::normalize(glm::dquat(s * 0.5, axis.x / s, axis.y / s, axis.z / s));
}

}  // namespace millsim
