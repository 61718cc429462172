#pragma once
#include "millsim/std/Group.h"

namespace millsim {

// Draws one of its children, or none: whichChoice indexes `children`.
class Switch : public GroupingNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  SFInt32 whichChoice{this, "whichChoice", Access::InputOutput, -1,
                      "Index of the child drawn; -1 (or any index out of range) draws none.",
                      Range::closed(-1e6, 1e6)};

  // The child drawn, or null.
  const ChildNode* chosen() const;
};

}  // namespace millsim
