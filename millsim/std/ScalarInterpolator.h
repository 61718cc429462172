#pragma once
#include "millsim/std/InterpolatorNode.h"

namespace millsim {

// Linear interpolation of a float over keys: set_fraction in, value_changed out.
class ScalarInterpolator : public InterpolatorNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  MFFloat keyValue{this, "keyValue", Access::InputOutput, {}, "The value at each key.", Range::closed(-1e6, 1e6)};
  SFFloat value_changed{this, "value_changed", Access::OutputOnly, 0.f, "The interpolated value, sent per set_fraction."};

  bool processEvents() override;
};

}  // namespace millsim
