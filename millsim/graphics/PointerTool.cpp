#include "millsim/graphics/PointerTool.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/matrix.hpp>

namespace millsim {

glm::dvec3 pointUnderCursor(const Camera& camera, double x, double y, const glm::dvec3& onPlaneOf) {
  const glm::dmat4 inverse = glm::inverse(camera.projection * camera.view);
  const double nx = 2.0 * x / std::max(camera.width, 1) - 1.0;
  const double ny = 1.0 - 2.0 * y / std::max(camera.height, 1);
  auto unproject = [&](double z) {
    const glm::dvec4 p = inverse * glm::dvec4(nx, ny, z, 1.0);
    return glm::dvec3(p) / p.w;
  };
  const glm::dvec3 a = unproject(-1.0), b = unproject(1.0);  // the ray through the pixel
  const glm::dvec3 forward = glm::normalize(glm::dvec3(glm::inverse(camera.view) * glm::dvec4(0.0, 0.0, -1.0, 0.0)));
  const double denom = glm::dot(b - a, forward);
  if (std::abs(denom) < 1e-300) return onPlaneOf;
  const double s = glm::dot(onPlaneOf - a, forward) / denom;
  return a + (b - a) * s;
}

void PointerTool::follow(const Camera& camera, double x, double y) {
  pose_.position = pointUnderCursor(camera, x, y, pose_.position);
}

void PointerTool::push(const Camera& camera, double notches) {
  const glm::dvec3 forward = glm::normalize(glm::dvec3(glm::inverse(camera.view) * glm::dvec4(0.0, 0.0, -1.0, 0.0)));
  pose_.position += forward * (notches * depthStep_);
}

void PointerTool::turn(const Camera& camera, double dx, double dy) {
  const glm::dmat4 toWorld = glm::inverse(camera.view);
  const glm::dvec3 right = glm::normalize(glm::dvec3(toWorld * glm::dvec4(1.0, 0.0, 0.0, 0.0)));
  const glm::dvec3 up = glm::normalize(glm::dvec3(toWorld * glm::dvec4(0.0, 1.0, 0.0, 0.0)));
  // Half a turn per window height, as EXAMINE turns the view.
  const double perPixel = std::numbers::pi / std::max(camera.height, 1);
  const glm::dquat q = glm::angleAxis(dx * perPixel, up) * glm::angleAxis(dy * perPixel, right);
  pose_.orientation = glm::normalize(q * pose_.orientation);
}

}  // namespace millsim
