#pragma once
#include <cstdint>

#include "millsim/std/EventNode.h"

namespace millsim {

// Spherical linear interpolation of a rotation over keys, along the shorter arc.
class OrientationInterpolator : public EventNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  SFFloat set_fraction{this, "set_fraction", Access::InputOnly, 0.f, "Where to interpolate, among the keys."};
  MFFloat key{this, "key", Access::InputOutput, {}, "Fractions, in non-decreasing order.", Range::closed(-1e6, 1e6)};
  MFRotation keyValue{this, "keyValue", Access::InputOutput, {}, "The orientation at each key."};
  SFRotation value_changed{this, "value_changed", Access::OutputOnly, Rotation{},
                           "The interpolated orientation, sent per set_fraction."};

  bool processEvents() override;
  bool hasPendingEvent() const override { return pending(set_fraction, seen_); }
  void dropPending() override { (void)takeEvent(set_fraction, seen_); }

private:
  std::uint64_t seen_ = 0;
};

}  // namespace millsim
