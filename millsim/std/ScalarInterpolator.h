#pragma once
#include <cstdint>

#include "millsim/std/EventNode.h"

namespace millsim {

// Linear interpolation of a float over keys: set_fraction in, value_changed out.
class ScalarInterpolator : public EventNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  SFFloat set_fraction{this, "set_fraction", Access::InputOnly, 0.f, "Where to interpolate, among the keys."};
  MFFloat key{this, "key", Access::InputOutput, {}, "Fractions, in non-decreasing order.", Range::closed(-1e6, 1e6)};
  MFFloat keyValue{this, "keyValue", Access::InputOutput, {}, "The value at each key.", Range::closed(-1e6, 1e6)};
  SFFloat value_changed{this, "value_changed", Access::OutputOnly, 0.f, "The interpolated value, sent per set_fraction."};

  bool processEvents() override;
  bool hasPendingEvent() const override { return pending(set_fraction, seen_); }
  void dropPending() override { (void)takeEvent(set_fraction, seen_); }

private:
  std::uint64_t seen_ = 0;
};

}  // namespace millsim
