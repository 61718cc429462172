#pragma once
// ExamineNavigator: X3D's EXAMINE navigation as the window does it — the camera
// orbits a centre (left-drag), dollies towards it (wheel) and slides with it
// (middle- or shift-drag). Pure camera maths, no GL, so it is tested alone.
#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

#include "millsim/graphics/SceneView.h"

namespace millsim {

class ExamineNavigator {
public:
  // Starts from `view`, orbiting `centre` (the viewpoint's centerOfRotation
  // or the scene's centre).
  void reset(const ViewSpec& view, const glm::dvec3& centre);

  // Mouse motion in pixels (x right, y down) in a window `height` pixels
  // tall: dragging the whole height turns the scene half a turn.
  void rotate(double dx, double dy, int height);
  // Wheel notches (positive: closer); each changes the distance by 10 %.
  void zoom(double notches);
  // Slides camera and centre so the point under the cursor follows it.
  void pan(double dx, double dy, int height);

  ViewSpec view() const;
  const glm::dvec3& centre() const { return centre_; }
  double distance() const { return distance_; }

private:
  glm::dquat orientation_{1.0, 0.0, 0.0, 0.0};
  glm::dvec3 centre_{0.0};
  double distance_ = 1.0;
  double fieldOfView_ = 0.7853981633974483;
};

}  // namespace millsim
