#pragma once
// PointerTool: the mouse as a 6-DOF device (MouseDevice), as H3DAPI's mouse
// haptics device does it. The burr follows the cursor on the plane through
// the burr parallel to the screen; Ctrl+wheel moves it along the line of
// sight; a right-drag turns the tool about the screen's axes through the burr
// centre. Pure camera maths, no GL and no window, so it is tested alone.
#include "millsim/graphics/SceneView.h"
#include "millsim/math/Pose.h"

namespace millsim {

// The world point under pixel (x, y) (from the top left) at the depth of
// `onPlaneOf` (the plane through it facing the camera).
glm::dvec3 pointUnderCursor(const Camera& camera, double x, double y, const glm::dvec3& onPlaneOf);

class PointerTool {
public:
  explicit PointerTool(const Pose& start = {}, double depthStep = 2e-4) : pose_(start), depthStep_(depthStep) {}

  // The cursor moved to pixel (x, y): the burr goes under it.
  void follow(const Camera& camera, double x, double y);
  // Wheel notches with the modifier: positive moves away from the viewer.
  void push(const Camera& camera, double notches);
  // Right-drag by (dx, dy) pixels: turns about the camera's up and right axes.
  void turn(const Camera& camera, double dx, double dy);

  const Pose& pose() const { return pose_; }
  void setPose(const Pose& pose) { pose_ = pose; }

private:
  Pose pose_;
  double depthStep_;
};

}  // namespace millsim
