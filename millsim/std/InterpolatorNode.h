#pragma once
// InterpolatorNode: what X3D's interpolators share — set_fraction in, the
// keys, and the event handling. Each one declares its keyValue and
// value_changed and says how two values mix (KeyFrames.h finds the keys).
#include <cstdint>
#include <utility>

#include "millsim/std/EventNode.h"
#include "millsim/std/KeyFrames.h"

namespace millsim {

class InterpolatorNode : public EventNode {
public:
  SFFloat set_fraction{this, "set_fraction", Access::InputOnly, 0.f, "Where to interpolate, among the keys."};
  MFFloat key{this, "key", Access::InputOutput, {}, "Fractions, in non-decreasing order.", Range::closed(-1e6, 1e6)};

  bool hasPendingEvent() const override { return pending(set_fraction, seen_); }
  void dropPending() override { (void)takeEvent(set_fraction, seen_); }

protected:
  // At a new set_fraction: sends the key values interpolated there (nothing
  // when there are none). True if it sent.
  template <class Values, class Out, class Mix> bool sendInterpolated(const Values& keyValue, Out& valueChanged, Mix&& mix) {
    if (!takeEvent(set_fraction, seen_)) return false;
    const auto v = interpolate(key.get(), keyValue.get(), set_fraction.get(), std::forward<Mix>(mix));
    if (!v) return false;
    valueChanged.set(*v);
    return true;
  }

private:
  std::uint64_t seen_ = 0;
};

}  // namespace millsim
