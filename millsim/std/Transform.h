#pragma once
#include <glm/mat4x4.hpp>

#include "millsim/std/Group.h"

namespace millsim {

// A grouping node that places its children in a frame of their own
// (Transform, MatrixTransform). SceneWalk, and so haptics, graphics and the
// assessment regions, apply localMatrix() to everything under it.
class TransformingNode : public GroupingNode {
public:
  // Child frame to parent frame.
  virtual glm::mat4 localMatrix() const = 0;
};

// Places its children in a new frame: translation, rotation and scale about a centre.
class Transform : public TransformingNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  SFVec3f translation{this, "translation", Access::InputOutput, glm::vec3(0.f), "Translation (m).", Range::closed(-1e4, 1e4).in(quantity::length)};
  SFRotation rotation{this, "rotation", Access::InputOutput, Rotation{}, "Rotation about center."};
  SFVec3f scale{this, "scale", Access::InputOutput, glm::vec3(1.f), "Scale factors along the scaleOrientation axes.",
                Range::openClosed(0, 1e4)};
  SFRotation scaleOrientation{this, "scaleOrientation", Access::InputOutput, Rotation{},
                              "Orientation of the scale axes."};
  SFVec3f center{this, "center", Access::InputOutput, glm::vec3(0.f), "Centre of rotation and scale (m).", Range::closed(-1e4, 1e4).in(quantity::length)};

  // The X3D transform: T·C·R·SR·S·SR⁻¹·C⁻¹, child frame to parent frame.
  glm::mat4 localMatrix() const override;
};

}  // namespace millsim
