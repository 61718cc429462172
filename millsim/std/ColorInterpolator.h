#pragma once
#include "millsim/std/InterpolatorNode.h"

namespace millsim {

// Interpolation of a colour over keys in HSV space (X3D 19.4.1): set_fraction
// in, value_changed out.
class ColorInterpolator : public InterpolatorNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  MFColor keyValue{this, "keyValue", Access::InputOutput, {}, "The colour (RGB) at each key.", Range::closed(0, 1)};
  SFColor value_changed{this, "value_changed", Access::OutputOnly, Color{},
                        "The interpolated colour, sent per set_fraction: mixed in HSV, the hue the shorter way round "
                        "the colour circle."};

  bool processEvents() override;

  // a and b mixed in HSV space, t the weight of b; the hue goes the shorter way round.
  static Color mixHsv(const Color& a, const Color& b, float t);
};

}  // namespace millsim
