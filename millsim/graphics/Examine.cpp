#include "millsim/graphics/Examine.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace millsim {

void ExamineNavigator::reset(const ViewSpec& view, const glm::dvec3& centre) {
  orientation_ = glm::normalize(view.orientation);
  fieldOfView_ = view.fieldOfView;
  const glm::dvec3 forward = glm::mat3_cast(orientation_) * glm::dvec3(0.0, 0.0, -1.0);
  // Orbit the point on the line of sight nearest the centre: the view does
  // not jump when navigation starts, and turning keeps the centre in view.
  const double along = std::max(glm::dot(centre - view.position, forward), 1e-6);
  centre_ = view.position + forward * along;
  distance_ = along;
}

void ExamineNavigator::rotate(double dx, double dy, int height) {
  const double perPixel = std::numbers::pi / std::max(height, 1);
  const glm::dmat3 axes = glm::mat3_cast(orientation_);
  // Yaw about the world's up (X3D: +Y), pitch about the camera's right: the
  // horizon stays level as in X3D browsers' EXAMINE mode.
  const glm::dquat yaw = glm::angleAxis(-dx * perPixel, glm::dvec3(0.0, 1.0, 0.0));
  const glm::dquat pitch = glm::angleAxis(-dy * perPixel, axes[0]);
  orientation_ = glm::normalize(yaw * pitch * orientation_);
}

void ExamineNavigator::zoom(double notches) {
  distance_ = std::clamp(distance_ * std::pow(0.9, notches), 1e-5, 1e4);
}

void ExamineNavigator::pan(double dx, double dy, int height) {
  const glm::dmat3 axes = glm::mat3_cast(orientation_);
  const double metresPerPixel = 2.0 * distance_ * std::tan(0.5 * fieldOfView_) / std::max(height, 1);
  centre_ += (-dx * axes[0] + dy * axes[1]) * metresPerPixel;
}

ViewSpec ExamineNavigator::view() const {
  ViewSpec v;
  v.orientation = orientation_;
  v.position = centre_ + glm::mat3_cast(orientation_) * glm::dvec3(0.0, 0.0, distance_);
  v.fieldOfView = fieldOfView_;
  return v;
}

}  // namespace millsim
