#pragma once
#include <cstdint>

#include "millsim/std/EventNode.h"

namespace millsim {

// Linear interpolation of a 3D vector over keys: set_fraction in, value_changed out.
class PositionInterpolator : public EventNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  SFFloat set_fraction{this, "set_fraction", Access::InputOnly, 0.f, "Where to interpolate, among the keys."};
  MFFloat key{this, "key", Access::InputOutput, {}, "Fractions, in non-decreasing order.", Range::closed(-1e6, 1e6)};
  MFVec3f keyValue{this, "keyValue", Access::InputOutput, {}, "The position at each key (m).",
                   Range::closed(-1e4, 1e4).in(quantity::length)};
  SFVec3f value_changed{this, "value_changed", Access::OutputOnly, glm::vec3(0.f),
                        "The interpolated position (m), sent per set_fraction."};

  bool processEvents() override;
  bool hasPendingEvent() const override { return pending(set_fraction, seen_); }
  void dropPending() override { (void)takeEvent(set_fraction, seen_); }

private:
  std::uint64_t seen_ = 0;
};

}  // namespace millsim
