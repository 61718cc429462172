#pragma once
#include <cstdint>

#include "millsim/std/EventNode.h"

namespace millsim {

// Interpolation of a colour over keys in HSV space (X3D 19.4.1): set_fraction
// in, value_changed out.
class ColorInterpolator : public EventNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  SFFloat set_fraction{this, "set_fraction", Access::InputOnly, 0.f, "Where to interpolate, among the keys."};
  MFFloat key{this, "key", Access::InputOutput, {}, "Fractions, in non-decreasing order.", Range::closed(-1e6, 1e6)};
  MFColor keyValue{this, "keyValue", Access::InputOutput, {}, "The colour (RGB) at each key.", Range::closed(0, 1)};
  SFColor value_changed{this, "value_changed", Access::OutputOnly, Color{},
                        "The interpolated colour, sent per set_fraction: mixed in HSV, the hue the shorter way round "
                        "the colour circle."};

  bool processEvents() override;
  bool hasPendingEvent() const override { return pending(set_fraction, seen_); }
  void dropPending() override { (void)takeEvent(set_fraction, seen_); }

  // a and b mixed in HSV space, t the weight of b; the hue goes the shorter way round.
  static Color mixHsv(const Color& a, const Color& b, float t);

private:
  std::uint64_t seen_ = 0;
};

}  // namespace millsim
