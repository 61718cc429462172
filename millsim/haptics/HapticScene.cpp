#include "millsim/haptics/HapticScene.h"

#include <cmath>

#include <glm/geometric.hpp>

namespace millsim {

glm::dvec3 HapticScene::outwardNormal(const glm::dvec3& world) const {
  const glm::dvec3 g = gradient(world);
  const double len = glm::length(g);
  return len > 1e-12 && std::isfinite(len) ? -g / len : glm::dvec3(0.0);
}

}  // namespace millsim
