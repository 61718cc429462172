#pragma once
#include "millsim/std/InterpolatorNode.h"

namespace millsim {

// Linear interpolation of a 3D vector over keys: set_fraction in, value_changed out.
class PositionInterpolator : public InterpolatorNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  MFVec3f keyValue{this, "keyValue", Access::InputOutput, {}, "The position at each key (m).",
                   Range::closed(-1e4, 1e4).in(quantity::length)};
  SFVec3f value_changed{this, "value_changed", Access::OutputOnly, glm::vec3(0.f),
                        "The interpolated position (m), sent per set_fraction."};

  bool processEvents() override;
};

}  // namespace millsim
