#pragma once
// A rigid pose in the world frame: the burr centre and the tool's orientation.
// The tool's shaft runs along its local +Y (X3D's cylinder axis).
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

}  // namespace millsim
