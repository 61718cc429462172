#pragma once
#include "millsim/std/InterpolatorNode.h"

namespace millsim {

// Spherical linear interpolation of a rotation over keys, along the shorter arc.
class OrientationInterpolator : public InterpolatorNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  MFRotation keyValue{this, "keyValue", Access::InputOutput, {}, "The orientation at each key."};
  SFRotation value_changed{this, "value_changed", Access::OutputOnly, Rotation{},
                           "The interpolated orientation, sent per set_fraction."};

  bool processEvents() override;
};

}  // namespace millsim
