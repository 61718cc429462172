#pragma once
#include <cstdint>

#include "millsim/std/EventNode.h"

namespace millsim {

// Turns a boolean event into an integer one: a TRUE set_boolean sends integerKey on triggerValue.
class IntegerTrigger : public EventNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  SFBool set_boolean{this, "set_boolean", Access::InputOnly, false, "A TRUE event here sends triggerValue."};
  SFInt32 integerKey{this, "integerKey", Access::InputOutput, -1, "The value triggerValue sends.",
                     Range::closed(-1e6, 1e6)};
  SFInt32 triggerValue{this, "triggerValue", Access::OutputOnly, 0, "integerKey, sent per TRUE set_boolean."};

  bool processEvents() override;
  bool hasPendingEvent() const override { return pending(set_boolean, seen_); }
  void dropPending() override { (void)takeEvent(set_boolean, seen_); }

private:
  std::uint64_t seen_ = 0;
};

}  // namespace millsim
