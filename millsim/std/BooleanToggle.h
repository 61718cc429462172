#pragma once
#include <cstdint>

#include "millsim/std/EventNode.h"

namespace millsim {

// A flip-flop: each TRUE on set_boolean negates toggle (and sends it).
class BooleanToggle : public EventNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  SFBool set_boolean{this, "set_boolean", Access::InputOnly, false, "A TRUE event here negates toggle."};
  SFBool toggle{this, "toggle", Access::InputOutput, false, "The state, sent each time it flips."};

  bool processEvents() override;
  bool hasPendingEvent() const override { return pending(set_boolean, seen_); }
  void dropPending() override { (void)takeEvent(set_boolean, seen_); }

private:
  std::uint64_t seen_ = 0;
};

}  // namespace millsim
