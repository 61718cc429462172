#pragma once
#include <cstdint>

#include "millsim/std/EventNode.h"

namespace millsim {

// MillSim's own event utility: a number in, a line of text out, so that a
// lesson can show a live value (VolumeObject.removedVolume, a device's
// force) in a Text. X3D routes join fields of one type only and X3D has no
// standard node for this (browsers use a Script). `scale` converts units:
// 1e9 shows m³ as mm³.
class NumberToText : public EventNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  SFFloat set_value{this, "set_value", Access::InputOnly, 0.f, "The number to show."};
  SFFloat scale{this, "scale", Access::InputOutput, 1.f, "Multiplies the number before it is written (1e9: m³ as mm³).",
                Range::closed(-1e15, 1e15)};
  SFInt32 decimals{this, "decimals", Access::InputOutput, 2, "Digits after the decimal point.", Range::closed(0, 9)};
  SFString prefix{this, "prefix", Access::InputOutput, "", "Text before the number."};
  SFString suffix{this, "suffix", Access::InputOutput, "", "Text after the number (its unit)."};
  MFString string_changed{this, "string_changed", Access::OutputOnly, {},
                          "prefix, the number, suffix: one line, sent per set_value (route it to a Text's string)."};

  bool processEvents() override;
  bool hasPendingEvent() const override { return pending(set_value, seen_); }
  void dropPending() override { (void)takeEvent(set_value, seen_); }

private:
  std::uint64_t seen_ = 0;
};

}  // namespace millsim
