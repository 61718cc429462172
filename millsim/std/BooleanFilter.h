#pragma once
#include <cstdint>

#include "millsim/std/EventNode.h"

namespace millsim {

// Splits a boolean event: TRUE goes out on inputTrue, FALSE on inputFalse, and the negation on inputNegate.
class BooleanFilter : public EventNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  SFBool set_boolean{this, "set_boolean", Access::InputOnly, false, "The event to filter."};
  SFBool inputTrue{this, "inputTrue", Access::OutputOnly, false, "Sent (TRUE) when set_boolean is TRUE."};
  SFBool inputFalse{this, "inputFalse", Access::OutputOnly, false, "Sent (FALSE) when set_boolean is FALSE."};
  SFBool inputNegate{this, "inputNegate", Access::OutputOnly, false, "Sent for every set_boolean, negated."};

  bool processEvents() override;
  bool hasPendingEvent() const override { return pending(set_boolean, seen_); }
  void dropPending() override { (void)takeEvent(set_boolean, seen_); }

private:
  std::uint64_t seen_ = 0;
};

}  // namespace millsim
