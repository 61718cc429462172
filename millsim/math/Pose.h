#pragma once
// A rigid pose in the world frame: the burr centre and the tool's orientation.
// The tool's shaft runs along its local +Y (X3D's cylinder axis).
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

namespace millsim {

struct Pose {
  glm::dvec3 position{0.0};
  glm::dquat orientation{1.0, 0.0, 0.0, 0.0};  // w, x, y, z

  glm::dvec3 shaftDirection() const { return orientation * glm::dvec3(0.0, 1.0, 0.0); }
};

inline bool isFinite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
inline bool isFinite(const Pose& p) {
  return isFinite(p.position) && std::isfinite(p.orientation.w) && std::isfinite(p.orientation.x) &&
         std::isfinite(p.orientation.y) && std::isfinite(p.orientation.z);
}

// The shortest rotation taking unit vector a to unit vector b (identity for
// a == b; a half turn about any perpendicular axis for a == −b).
glm::dquat rotationBetween(const glm::dvec3& a, const glm::dvec3& b);

// Two unit vectors perpendicular to unit n and to each other: t1 = n × the
// world axis least aligned with n (normalised), t2 = n × t1. The tangent
// plane the renderers' sphere, line and slide searches step in. Callers name
// the two (`const glm::dvec3 t1 = b.t1`), not `auto [t1, t2]`: clang 14, the
// ASan stage's compiler, cannot capture a structured binding in a lambda.
struct Tangents {
  glm::dvec3 t1, t2;
};
inline Tangents tangentsOf(const glm::dvec3& n) {
  const glm::dvec3 t1 = glm::normalize(glm::cross(n, std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
  return {t1, glm::cross(n, t1)};
}

}  // namespace millsim
